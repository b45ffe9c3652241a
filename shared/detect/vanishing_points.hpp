// Stage 2 of detection: the two families of grid lines. Every edgel lies on
// a line of the grid; the lines of one family meet in a vanishing point (at
// infinity when the camera looks straight at the screen). Edgels from text
// and pictures belong to neither and are left out.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "shared/detect/edgels.hpp"

namespace umf {

struct LineFamily {
    // Homogeneous image point, unit length; its third coordinate is about 0
    // when the lines are parallel in the image.
    Eigen::Vector3d vanishing_point = Eigen::Vector3d::Zero();
    std::vector<int> edgels;  // indices into the edgel list of the lines through it
};

struct VanishingPoints {
    bool found = false;
    LineFamily family[2];
};

struct VanishingOptions {
    double min_separation_deg = 20;  // between the two families' main directions in the image
    double inlier_deg = 4;           // edgel direction against the direction to the vanishing point
    // Noisy edgels get more: their gradient's direction is uncertain by
    // about 3.5 sigma / |gradient| radians (Sobel), and this many of those
    // are allowed, up to max_inlier_deg.
    double noise_deviations = 4;
    double max_inlier_deg = 15;
    int ransac_iterations = 64;      // per family
    int min_edgels = 10;             // per family
    std::uint64_t seed = 1;
};

// `width` and `height` are the image's, for numerically sound coordinates.
// `noise_sigma`: the image's noise in grey levels (EdgelScan::noise_sigma).
VanishingPoints find_vanishing_points(const std::vector<Edgel>& edgels, int width, int height,
                                      const VanishingOptions& options = {}, double noise_sigma = 0);

// The direction (unit, image coordinates) from an image point towards a
// vanishing point, or along it when it is at infinity.
Eigen::Vector2d direction_to(const Eigen::Vector3d& vanishing_point, const Eigen::Vector2d& from);

}  // namespace umf
