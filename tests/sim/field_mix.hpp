// The provider's side of the simulation: the field blended into the screen.
//
// Coordinates: field point (u, v) is in module units, (0, 0) being the
// top-left corner of module (row 0, column 0), so module (i, j) covers
// u in [j, j + 1], v in [i, i + 1]. Screen points are continuous pixel
// coordinates: pixel (x, y) covers [x, x + 1) x [y, y + 1), its centre is
// (x + 0.5, y + 0.5). A placement maps one to the other:
// screen = origin + module_px * (u, v).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

#include "shared/field/field.hpp"

namespace umf::sim {

struct FieldPlacement {
    cv::Point2d origin;  // screen position of field point (0, 0)
    double module_px = 1;
};

cv::Point2d field_to_screen(const FieldPlacement& placement, cv::Point2d field_uv);
cv::Point2d screen_to_field(const FieldPlacement& placement, cv::Point2d screen_px);

// The field centred on a screen of the given size at the given module size.
FieldPlacement centred_placement(const Field& field, cv::Size screen, double module_px);

// The field's palette as BGR; the grey palette when the field has none.
std::vector<cv::Vec3b> palette_bgr(const Field& field);

// Each screen pixel whose centre lies on the field (0 <= u < width,
// 0 <= v < height) becomes (1 - opacity) * content + opacity * colour of the
// module under its centre, rounded; every other pixel is left as it is.
// Sampling at pixel centres is what a compositor drawing the field without
// antialiasing does: with fractional module sizes, modules come out one
// pixel wider or narrower here and there, but no pixel is a blend of two.
cv::Mat mix_field(const cv::Mat& screen_bgr, const Field& field, const FieldPlacement& placement, double opacity);

}  // namespace umf::sim
