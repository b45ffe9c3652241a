// The field mixed into a screen image, as the provider shows it: the same
// pixels for compose, the headless provider and (later) the overlay, so that
// a screenshot of one is a screenshot of the others. No Qt or OpenCV here:
// the web client builds shared/ with emscripten.
//
// Each pixel whose centre (x + 0.5, y + 0.5) lies on the field
// (0 <= u < width, 0 <= v < height under the placement) becomes
// round((1 - a) * content + a * colour) of the module under that centre, per
// channel; every other pixel, and any alpha channel, is left as it is.
// Sampling at pixel centres is what a compositor drawing the field without
// antialiasing does: no pixel is a blend of two modules. The camera
// simulator's sim::mix_field (tests/sim) is the reference, byte for byte.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shared/field/field.hpp"
#include "shared/overlay/placement.hpp"

namespace umf::overlay {

// An 8-bit interleaved image the caller owns, changed in place.
struct PixelBuffer {
    std::uint8_t* data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride_bytes = 0;  // from one row to the next; at least width * channels
    int channels = 3;                 // 3, or 4 with the alpha (or padding) byte last
    bool bgr = false;                 // byte order B, G, R (Qt's RGB32 on little-endian, OpenCV) rather than R, G, B
};

// The colours a field is shown in: `palette` when not empty ("#rrggbb" per
// field colour, extra entries unused), else the field's own palette, else
// greys from black to white. Throws std::invalid_argument for a palette
// entry that is not "#rrggbb" or too few colours for the field.
std::vector<std::array<std::uint8_t, 3>> field_colours_rgb(const Field& field, const std::vector<std::string>& palette);

// Mixes the field in at `opacity` (0..1). Throws std::invalid_argument for a
// buffer that cannot be what it says (no data, sizes, stride, channels), a
// module size that is not positive and finite, an opacity outside 0..1, or a
// palette field_colours_rgb refuses.
void mix_field(const PixelBuffer& image, const Field& field, const FieldPlacement& placement, double opacity,
               const std::vector<std::string>& palette = {});

}  // namespace umf::overlay
