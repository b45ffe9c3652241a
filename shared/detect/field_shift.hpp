// Where a frame's own field lies against a place: the field's modules, drawn
// where the place's map puts them, correlated with the frame's detail at
// shifts of a few pixels. A place read from an image made of many frames
// (pulse_search.hpp) is where those frames together put the field; the
// newest frame's field lies elsewhere when its registration onto them was a
// pixel or two off, and every frame's field is faint under its content. One
// module's edge says little there, but a view holds thousands of them, and
// the content's edges fall on them at random: their sum singles out a shift.
#pragma once

#include <Eigen/Core>

#include "shared/detect/image.hpp"
#include "shared/field/field.hpp"

namespace umf {

struct FieldShiftOptions {
    // Shifts tried each way, whole pixels, then refined between them: this
    // share of a module at the frame's centre, at most max_reach_px.
    double reach_modules = 0.75;
    int max_reach_px = 12;
    // The frame's gradients clipped at this many times their median.
    float clip_medians = 3;
};

struct FieldShift {
    bool measured = false;    // the place puts enough of the field in the frame
    Eigen::Vector2d shift = Eigen::Vector2d::Zero();  // the frame's field less the place's (pixels)
    // The evidence for the shift and for no shift: the correlation over its
    // own spread (a t-value), at the best whole-pixel shift and at none.
    double best_t = 0, place_t = 0;
    // The most the content alone gives at those shifts: the same, for the
    // field's pattern a few modules along (another pattern on the same grid).
    double content_t = 0;
    int edge_pixels = 0;  // pixels on the drawn field's module edges
    double module_px = 0;  // a module's side at the frame's centre
};

// `image_to_field`: the place, image pixels to field modules (u, v).
FieldShift field_shift(const GreyView& frame, const Field& field, const Eigen::Matrix3d& image_to_field,
                       const FieldShiftOptions& options = {});

}  // namespace umf
