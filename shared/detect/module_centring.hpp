// Where a place's module centres sit on the field's modules, around one
// point. A homography about half a module off there still reads nearly
// every module right, so the checks accept it; but the refit's searches for
// module edges, each within 0.4 module of its prediction, then find the true
// edge and its neighbour about equally often, and the fit can go either way.
// The image sampled at the module centres, each sample weighted by its
// module's brightness less their mean, sums high while the centres stay
// inside their modules and falls off as they cross the modules' edges: the
// middle of the shifts where it sums high is a start for the refit within
// a tenth of a module.
#pragma once

#include <Eigen/Core>
#include <span>

#include "shared/detect/image.hpp"
#include "shared/field/field.hpp"

namespace umf {

struct CentringOptions {
    int radius = 4;       // modules each way from the point: (2 radius + 1) squared, at most 8
    double step = 0.125;  // shifts tried this far apart (modules) ...
    int steps = 8;        // ... this many each way along each axis, at most 16
};

// `brightness`: module_brightness(field). The shift s (field modules) that
// puts the module centres on the modules: field_to_image * translation(s)
// is the homography centred there, and the point `at` lies at at - s under
// it. Zero when too little around `at` is in the image.
Eigen::Vector2d centring_shift(const GreyView& image, const Field& field, std::span<const double> brightness,
                               const Eigen::Matrix3d& field_to_image, const Eigen::Vector2d& at,
                               const CentringOptions& options = {});

}  // namespace umf
