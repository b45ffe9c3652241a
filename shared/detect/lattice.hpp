// A try for modules of 3-5 camera pixels: the field's grid read from
// the spectrum of edge strength around the aim, with no edgels, directions
// or lines. At that size a 3 x 3 gradient reaches into the neighbouring
// modules' edges and points up to 30 degrees off its line's normal, so the
// vanishing points and grid lines fail; yet module edges fall only on the
// grid lines, so the strength of the edges is periodic along both grid
// directions, and its spectrum peaks at the two module frequencies. Each
// peak gives a direction and a spacing, its phase where the lines lie: over
// a patch of a few dozen modules, the grid as an affine map, which the
// module reading, the window vote and the refit (refine.hpp) then take on.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "shared/detect/image.hpp"

namespace umf {

struct LatticeOptions {
    int patch_px = 128;              // the square read around the aim; a power of two
    double min_period_px = 2.5;      // module sizes looked for
    double max_period_px = 12;
    double min_angle_deg = 40;       // between the two grid directions (a steep view narrows the right angle)
    double max_period_ratio = 1.67;  // between the two spacings (foreshortening)
    int max_lattices = 3;            // from the strongest peaks, best first
    double min_peak_to_mean = 4;     // a peak's magnitude over the band's mean
};

struct Lattice {
    Eigen::Matrix3d grid_to_image;  // grid point (x, y) -> image; cell (i, j) covers x in [j, j+1], y in [i, i+1]
    int rows = 0, cols = 0;         // the cells covering the patch
    double period_px[2] = {0, 0};   // module spacing along each direction
};

// Up to options.max_lattices lattices, the likeliest first; none when the
// image is smaller than the patch or the spectrum has no two peaks that
// could be a grid.
std::vector<Lattice> find_lattices(const GreyView& image, const Eigen::Vector2d& aim, const LatticeOptions& options = {});

}  // namespace umf
