// The screen content under the field blurred before the field is mixed in
// (a preset's `blur`). Text, window borders and icons are edges at about the
// scale of a module; the detector's edgels, grid lines and module reading all
// have to reject them. Blurred away, they no longer compete with the field's
// own (still sharp) module edges, so the field is found at a lower opacity.
// Compose, the board window and the tuning preview share this, so they blur
// alike. No throw here: the web client may build shared/ without exceptions;
// a buffer that cannot be what it says is reported by the return value.
#pragma once

#include "shared/overlay/field_mix.hpp"
#include "shared/overlay/placement.hpp"

namespace umf::overlay {

// Pixels x0 <= x < x1, y0 <= y < y1.
struct PixelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool operator==(const PixelBox&) const = default;
};

// The pixels whose centres lie on a field of field_width x field_height
// modules under `placement` (the pixels mix_field changes), clipped to the
// image; empty when they do not meet or the placement is not finite.
PixelBox field_pixels(const FieldPlacement& placement, int field_width, int field_height, int image_width,
                      int image_height);

// The blur's Gaussian-equivalent standard deviation in pixels: strength
// (clamped to 0..1; NaN counts as 0) times half a module.
double blur_sigma_px(double strength, double module_px);

// Blurs the colour bytes of `box` (clipped to the image) in place: three
// running-sum box passes per axis, widths chosen so their variance is
// blur_sigma_px's, each pass mirrored at the box's border (content outside
// the box neither bleeds in nor is changed, and the box's mean is kept). A 4th byte (alpha or padding)
// is left as it is. Strength 0, or a sigma too small for a 3-pixel box,
// changes nothing. Returns false, changing nothing, for a buffer that cannot
// be what it says (no data, negative size, channels not 3 or 4, stride below
// a row) or a module size that is not positive and finite.
[[nodiscard]] bool blur_background(const PixelBuffer& image, PixelBox box, double strength, double module_px);

// blur_background over field_pixels: the content under the field, as the
// field will be mixed into it.
[[nodiscard]] bool blur_under_field(const PixelBuffer& image, int field_width, int field_height,
                                    const FieldPlacement& placement, double strength);

}  // namespace umf::overlay
