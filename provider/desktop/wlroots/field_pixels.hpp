// The field's pixels for a layer surface that cannot have the compositor's
// opacity (no wp_alpha_modifier_v1 in sway 1.7): the pulse goes into the
// buffer, premultiplied ARGB8888, the field layer scaled by the opacity.
// Kept cheap for 60 frames a second: the layer's rows repeat within a module
// row, so each opacity step is one row per distinct row (cached), copied
// down; only the field's box is written, and with a focus circle only the
// circle's box.
#pragma once

#include <QImage>
#include <QPointF>
#include <cstdint>
#include <map>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// The opacity as the 8-bit step a buffer can show.
int opacity_level(double opacity);

// A premultiplied pixel scaled by factor / 65025 (255 * 255 = all of it).
inline std::uint32_t scaled_pixel(std::uint32_t p, std::uint32_t factor) {
    const auto part = [factor](std::uint32_t c) { return (c * factor + 32512u) / 65025u; };
    return part(p >> 24) << 24 | part((p >> 16) & 0xffu) << 16 | part((p >> 8) & 0xffu) << 8 | part(p & 0xffu);
}

// The soft circle: 255 within (1 - softness) of the radius, falling linearly
// to 0 at it (as the X11 overlay's gradient mask), over the pixels of `box`.
struct FocusMask {
    WindowRect box;  // clipped to the surface
    std::vector<std::uint8_t> alpha;
};
FocusMask focus_mask(QPointF centre, double radius, int width, int height);

class PulsedField {
public:
    // `layer` from field_layer(): premultiplied, opaque where the field is.
    explicit PulsedField(QImage layer);

    int width() const { return layer_.width(); }
    int height() const { return layer_.height(); }
    // The smallest box holding every pixel of the field (empty without one).
    const WindowRect& field_box() const { return box_; }

    // The field at `level` (0..255) into field_box() of `pixels` (rows of
    // `stride` bytes, the surface's size).
    void paint(std::uint8_t* pixels, int stride, int level);
    // The field at `level` within the mask, into the mask's box only.
    void paint_focus(std::uint8_t* pixels, int stride, int level, const FocusMask& mask) const;

private:
    const std::vector<std::uint32_t>& rows_at(int level);

    QImage layer_;
    WindowRect box_;
    std::vector<int> group_of_row_;     // per row of the box: its distinct row
    std::vector<int> group_first_row_;  // per distinct row: a row of the layer showing it
    std::map<int, std::vector<std::uint32_t>> levels_;  // level -> distinct rows at it
};

}  // namespace umf::provider
