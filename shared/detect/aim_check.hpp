// The last check of a place: the modules right around the aim point must
// read as the field there, and better than the field shifted by one module
// any way. A homography fitted where most windows voted can be right there
// and still bend away by half a module or more at the aim (a steep view, a
// rolling shutter, a fit pulled by content): the whole view then reads as
// the field, and only the aim's own neighbourhood shows the error.
#pragma once

#include <Eigen/Core>

#include "shared/detect/module_grid.hpp"
#include "shared/detect/placement_vote.hpp"
#include "shared/detect/window_index.hpp"

namespace umf {

struct AimCheckOptions {
    int radius = 3;                // modules read around the aim's: (2 radius + 1) squared
    double min_margin_bits = 10;   // the place's evidence over the best one-module shift
};

// `grid` holds the modules read under the place's homography for field rows
// from `row0` and columns from `col0` (turn 0); `aim_field` is the aim point
// in field coordinates (modules). True when the aim's neighbourhood singles
// out the place, and when the aim lies off the field, where there is nothing
// to read.
bool aim_holds(const ModuleGrid& grid, int row0, int col0, const Eigen::Vector2d& aim_field, const WindowIndex& index,
               const VoteOptions& vote, const AimCheckOptions& options = {});

}  // namespace umf
