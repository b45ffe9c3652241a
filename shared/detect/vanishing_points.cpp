#include "shared/detect/vanishing_points.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace umf {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kJudges = 160;

// Edgels in coordinates centred on the image and scaled to about [-1, 1], so
// homogeneous vectors stay well conditioned; lines as unit normals and offsets.
struct EdgelLine {
    Eigen::Vector2d p;   // position, normalised coordinates
    Eigen::Vector2d d;   // unit direction of the edge (perpendicular to the gradient)
    Eigen::Vector3d l;   // the line through p along d
    double angle;        // of d, in [0, pi)
    double weight;       // gradient magnitude
    double cos_tol;      // alignment needed to count as an inlier
};

// For angles in [0, 2 pi), as every one here is; the subtraction is exact there.
double angle_between_mod_pi(double a, double b) {
    double d = std::abs(a - b);
    if (d >= kPi) d -= kPi;
    return std::min(d, kPi - d);
}

// An angle from atan2 taken into [0, pi): what fmod(a + 2 pi, pi) gives,
// bit for bit (each subtraction is exact), without its division loop.
double angle_mod_pi(double a) {
    double r = a + 2 * kPi;
    if (r >= 2 * kPi) r -= 2 * kPi;
    if (r >= kPi) r -= kPi;
    return r;
}

// Whether an edgel points at the vanishing point v within its tolerance:
// alignment(e, v) >= e.cos_tol without the root and division, for the
// thousands of tests a RANSAC makes.
bool aligned(const EdgelLine& e, const Eigen::Vector3d& v) {
    const Eigen::Vector2d w = v.head<2>() - v.z() * e.p;
    const double n2 = w.squaredNorm();
    if (n2 < 1e-24) return true;
    const double dot = w.dot(e.d);
    return dot * dot >= e.cos_tol * e.cos_tol * n2;
}

// Cosine of the angle between an edgel's direction and the direction from it
// to the vanishing point v (homogeneous, normalised coordinates).
double alignment(const EdgelLine& e, const Eigen::Vector3d& v) {
    const Eigen::Vector2d w = v.head<2>() - v.z() * e.p;
    const double n = w.norm();
    if (n < 1e-12) return 1.0;  // the vanishing point lies on the edgel itself
    return std::abs(w.dot(e.d)) / n;
}

// The point minimising the weighted squared distances to the lines: the
// eigenvector of the smallest eigenvalue of sum w l l^T. The algebraic
// distance l.v grows with the edgel's distance to the point, so a few rounds
// reweight it into the angle each edgel makes, which is what is measured.
Eigen::Vector3d fit_point(const std::vector<EdgelLine>& lines, const std::vector<int>& members) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int round = 0; round < 4; ++round) {
        // The solver reads the lower triangle alone: only it is summed.
        double m00 = 0, m10 = 0, m11 = 0, m20 = 0, m21 = 0, m22 = 0;
        for (int i : members) {
            double w = lines[i].weight;
            if (round > 0) {
                const double reach = (v.head<2>() - v.z() * lines[i].p).squaredNorm();
                w /= std::max(reach, 1e-6);
            }
            const Eigen::Vector3d& l = lines[i].l;
            const double a0 = w * l.x(), a1 = w * l.y(), a2 = w * l.z();
            m00 += a0 * l.x();
            m10 += a1 * l.x();
            m11 += a1 * l.y();
            m20 += a2 * l.x();
            m21 += a2 * l.y();
            m22 += a2 * l.z();
        }
        Eigen::Matrix3d m;
        m << m00, 0, 0, m10, m11, 0, m20, m21, m22;
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
        v = eig.eigenvectors().col(0).normalized();
    }
    return v;
}

// Strongest direction in a weighted histogram of edge angles, optionally
// away from another one.
double dominant_angle(const std::vector<EdgelLine>& lines, double avoid, double min_separation) {
    constexpr int kBins = 90;
    double hist[kBins] = {};
    for (const auto& e : lines) {
        if (avoid >= 0 && angle_between_mod_pi(e.angle, avoid) < min_separation) continue;
        hist[static_cast<int>(e.angle / kPi * kBins) % kBins] += e.weight;
    }
    int best = -1;
    double best_value = 0;
    for (int b = 0; b < kBins; ++b) {
        const double v = hist[(b + kBins - 1) % kBins] + 2 * hist[b] + hist[(b + 1) % kBins];
        if (v > best_value) {
            best_value = v;
            best = b;
        }
    }
    return best < 0 ? -1 : (best + 0.5) * kPi / kBins;
}

// The cosines of VanishingOptions' two bounds on an edgel's tolerance: most
// edgels get one of them.
struct ToleranceBounds {
    double cos_least, cos_most;
    explicit ToleranceBounds(const VanishingOptions& o)
        : cos_least(std::cos(std::min(o.max_inlier_deg, o.inlier_deg) * kPi / 180)),
          cos_most(std::cos(o.max_inlier_deg * kPi / 180)) {}
};

// Cosine of the angle an edgel may make with the direction to its vanishing
// point: a Sobel gradient's direction is uncertain by about 3.46 sigma / |g|
// radians for pixel noise sigma.
double inlier_cos(double g, double noise_sigma, const VanishingOptions& o, const ToleranceBounds& bounds) {
    const double tol_deg =
        std::min(o.max_inlier_deg, std::max(o.inlier_deg, o.noise_deviations * 3.46 * noise_sigma / g * 180 / kPi));
    if (tol_deg == o.max_inlier_deg) return bounds.cos_most;
    if (tol_deg == std::min(o.max_inlier_deg, o.inlier_deg)) return bounds.cos_least;
    return std::cos(tol_deg * kPi / 180);
}

// The noise that the candidates' scatter about the vanishing point v shows,
// from the lower quartile of angle x |g| / 3.46 (0.319 deviations of a
// normal distribution; the lower quartile leaves out the content's edges,
// which lie anywhere in the range). Compression flattens the areas the
// image's noise is estimated from while its ringing, like the corners of
// small modules, still tilts the gradients on the edges.
double scatter_noise(const std::vector<EdgelLine>& lines, const std::vector<int>& candidates,
                     const Eigen::Vector3d& v, const VanishingOptions& o) {
    const double cos_widest = std::cos(o.max_inlier_deg * kPi / 180);
    std::vector<double> x;
    for (int i : candidates) {
        const double a = alignment(lines[i], v);
        if (a >= cos_widest) x.push_back(std::acos(std::min(1.0, a)) * lines[i].weight / 3.46);
    }
    if (static_cast<int>(x.size()) < o.min_edgels) return 0;
    const auto q = x.begin() + static_cast<std::ptrdiff_t>(x.size() / 4);
    std::nth_element(x.begin(), q, x.end());
    return *q / 0.319;
}

}  // namespace

Eigen::Vector2d direction_to(const Eigen::Vector3d& v, const Eigen::Vector2d& from) {
    Eigen::Vector2d w = v.head<2>() - v.z() * from;
    const double n = w.norm();
    return n > 0 ? Eigen::Vector2d(w / n) : Eigen::Vector2d(1, 0);
}

VanishingPoints find_vanishing_points(const std::vector<Edgel>& edgels, int width, int height,
                                      const VanishingOptions& o, double noise_sigma) {
    VanishingPoints out;
    const double cx = width / 2.0, cy = height / 2.0, scale = std::max(width, height) / 2.0;
    std::vector<EdgelLine> lines;
    lines.reserve(edgels.size());
    const ToleranceBounds bounds(o);
    for (const auto& e : edgels) {
        const double g = std::hypot(e.gx, e.gy);
        if (g <= 0) continue;
        EdgelLine l;
        l.p = {(e.x - cx) / scale, (e.y - cy) / scale};
        l.d = {-e.gy / g, e.gx / g};
        l.l = Eigen::Vector3d(e.gx / g, e.gy / g, -(e.gx * l.p.x() + e.gy * l.p.y()) / g);
        l.angle = angle_mod_pi(std::atan2(l.d.y(), l.d.x()));
        l.weight = g;
        l.cos_tol = inlier_cos(g, noise_sigma, o, bounds);
        lines.push_back(l);
    }
    if (static_cast<int>(lines.size()) < 2 * o.min_edgels) return out;

    const double separation = o.min_separation_deg * kPi / 180;
    std::mt19937_64 rng(o.seed);
    std::vector<bool> taken(lines.size(), false);
    double first = -1;
    for (int f = 0; f < 2; ++f) {
        const double main = dominant_angle(lines, f == 0 ? -1 : first, separation);
        if (main < 0) return out;
        if (f == 0) first = main;
        // Candidates: edgels not taken whose direction is nearer this family's
        // main direction than the other's (perspective fans a family out).
        std::vector<int> candidates;
        for (int i = 0; i < static_cast<int>(lines.size()); ++i) {
            if (taken[i]) continue;
            const double to_main = angle_between_mod_pi(lines[i].angle, main);
            if (to_main < std::max(separation, 35 * kPi / 180) &&
                (f == 1 || to_main < angle_between_mod_pi(lines[i].angle, main + kPi / 2) + 1e-9))
                candidates.push_back(i);
        }
        if (static_cast<int>(candidates.size()) < o.min_edgels) return out;

        auto inliers_of = [&](const Eigen::Vector3d& v) {
            std::vector<int> in;
            for (int i : candidates)
                if (aligned(lines[i], v)) in.push_back(i);
            return in;
        };
        // Hypotheses are scored on an evenly spread subset of the candidates:
        // a few hundred edgels tell a good vanishing point from a bad one as
        // well as all of them, at a fraction of the cost.
        std::vector<int> judges;
        const std::size_t judge_stride = std::max<std::size_t>(1, candidates.size() / kJudges);
        for (std::size_t i = 0; i < candidates.size(); i += judge_stride) judges.push_back(candidates[i]);
        // A hypothesis's score, or any score no more than `beat` once it
        // cannot exceed it: only a better one than the best so far counts.
        auto score = [&](const Eigen::Vector3d& v, int beat) {
            int n = 0, left = static_cast<int>(judges.size());
            for (auto i = judges.begin(); i != judges.end() && n + left > beat; ++i, --left) n += aligned(lines[*i], v);
            return n;
        };
        Eigen::Vector3d best_v = Eigen::Vector3d::Zero();
        int best_score = -1;
        for (int it = 0; it < o.ransac_iterations; ++it) {
            const int a = candidates[rng() % candidates.size()], b = candidates[rng() % candidates.size()];
            Eigen::Vector3d v;
            if (a == b || angle_between_mod_pi(lines[a].angle, lines[b].angle) < 1e-4) {
                // Nearly parallel pair: their common direction is a candidate at infinity.
                v = Eigen::Vector3d(lines[a].d.x(), lines[a].d.y(), 0);
            } else {
                v = lines[a].l.cross(lines[b].l);
                if (v.norm() < 1e-12) continue;
                v.normalize();
            }
            const int s = score(v, best_score);
            if (s > best_score) {
                best_score = s;
                best_v = v;
            }
        }
        if (best_score < 0) return out;
        if (const double seen = scatter_noise(lines, candidates, best_v, o); seen > noise_sigma)
            for (int i : candidates) lines[i].cos_tol = inlier_cos(lines[i].weight, seen, o, bounds);
        std::vector<int> best = inliers_of(best_v);
        if (static_cast<int>(best.size()) < o.min_edgels) return out;
        Eigen::Vector3d v = fit_point(lines, best);
        for (int round = 0; round < 2; ++round) {
            auto in = inliers_of(v);
            if (in.size() < best.size()) break;
            best = std::move(in);
            v = fit_point(lines, best);
        }
        for (int i : best) taken[i] = true;
        // Back to pixel coordinates: x_pixel = scale * x + c.
        Eigen::Matrix3d denorm;
        denorm << scale, 0, cx, 0, scale, cy, 0, 0, 1;
        out.family[f].vanishing_point = (denorm * v).normalized();
        out.family[f].edgels = std::move(best);
    }
    out.found = true;
    return out;
}

}  // namespace umf
