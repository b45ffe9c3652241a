// Plane-to-plane homographies from point correspondences or from points
// measured on lines: the normalised direct linear transform, and a robust
// fit that ignores wrong matches.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace umf {

using Point2 = Eigen::Vector2d;

// H maps `from` to `to` in homogeneous coordinates, scaled so H(2,2) = 1 where
// possible. Nothing when there are fewer than four points or they are
// degenerate (three or more on one line among four, all coincident...).
std::optional<Eigen::Matrix3d> fit_homography(const std::vector<Point2>& from, const std::vector<Point2>& to);

// H maps each `from[i]` onto the line through `to[i]` across `normal[i]` (a
// unit vector in `to`'s plane): an edge found by searching across it says
// where the edge is, not where along it the search started. Minimises the
// distances from those lines (times each point's homogeneous weight).
// Nothing for fewer than eight points or lines that do not pin H down
// (all parallel...). With `along_weight` > 0 each point is also drawn to
// `to[i]` along its line, that many times as weakly: where the lines of a
// part of the view run mostly one way (a smear leaves the edges along it),
// they leave the fit free along them.
std::optional<Eigen::Matrix3d> fit_homography_to_lines(const std::vector<Point2>& from, const std::vector<Point2>& to,
                                                       const std::vector<Point2>& normal, double along_weight = 0);

// Nothing when the point maps to infinity.
std::optional<Point2> apply_homography(const Eigen::Matrix3d& h, const Point2& p);

// The map's derivative at a point (column j: how the image of `at` moves per
// unit along coordinate j there); nothing when the point maps to infinity.
std::optional<Eigen::Matrix2d> homography_derivative(const Eigen::Matrix3d& h, const Point2& at);

// How far apart two maps put the points of a square ring `reach` around `at`
// (its corners and edge middles) once both are moved to agree at `at`: how
// much their shapes differ there, in the maps' units (infinity where either
// sends a point to infinity).
double shape_distance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, const Point2& at, double reach);

struct RobustHomography {
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    std::vector<bool> inlier;
    int inliers = 0;
};

// RANSAC over four-point samples, then a refit to all inliers (points whose
// transfer error is at most `tolerance`, in the units of `to`). It draws at
// most `iterations` samples, fewer once one of four inliers has come up with
// 99.99 % probability at the best inlier share seen. Deterministic for a
// given seed.
std::optional<RobustHomography> fit_homography_robust(const std::vector<Point2>& from, const std::vector<Point2>& to,
                                                      double tolerance, int iterations = 200,
                                                      std::uint64_t seed = 1);

}  // namespace umf
