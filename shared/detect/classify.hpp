// Stage 4 of detection: reading the modules. With the grid's homography
// known, the centre of every module in view is sampled; module values (binary
// fields) come from a threshold between the two brightness clusters, edge
// signs (k-ary fields) from the difference of neighbouring centres.
#pragma once

#include <Eigen/Core>

#include "shared/detect/image.hpp"
#include "shared/detect/module_grid.hpp"

namespace umf {

struct ClassifyOptions {
    // Modules whose brightness lies within this fraction of the gap between
    // the two clusters from the threshold stay unknown rather than guessed.
    double doubt = 0.15;
    // Edge signs: a step below this fraction of the typical step is flat.
    double flat_step = 0.35;
};

// `grid_to_image` maps grid point (x, y) (cell (i, j) covers x in [j, j+1],
// y in [i, i+1]) to the image; the grid has `rows` x `cols` cells starting at 0.
ModuleGrid classify_modules(const GreyView& image, const Eigen::Matrix3d& grid_to_image, int rows, int cols,
                            int colors, bool edge_key, const ClassifyOptions& options, long& pixels_visited);

}  // namespace umf
