#include "provider/desktop/x11/x11_pixels.hpp"

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace umf::provider {

namespace {

// Shift and width of a colour mask: 0xff0000 -> (16, 8).
std::pair<int, int> mask_shape(unsigned long mask) {
    if (!mask) return {0, 0};
    return {std::countr_zero(mask), std::popcount(mask)};
}

std::uint32_t channel_to_8bit(unsigned long pixel, std::pair<int, int> shape) {
    const auto [shift, bits] = shape;
    if (bits == 0) return 0;
    const unsigned long value = (pixel >> shift) & ((1ul << bits) - 1);
    return static_cast<std::uint32_t>(bits >= 8 ? value >> (bits - 8) : value * 255 / ((1ul << bits) - 1));
}

bool is_host_order_xrgb(const XImage& image) {
    const int host_order = std::endian::native == std::endian::little ? LSBFirst : MSBFirst;
    return image.bits_per_pixel == 32 && image.byte_order == host_order && image.red_mask == 0xff0000 &&
           image.green_mask == 0xff00 && image.blue_mask == 0xff;
}

}  // namespace

Capture capture_from_ximage(XImage& image, int visual_class) {
    if (visual_class != -1 && visual_class != TrueColor && visual_class != DirectColor)
        throw std::runtime_error("X11: snapshots need a true colour screen");
    Capture capture{image.width, image.height, {}};
    capture.pixels.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
    if (is_host_order_xrgb(image)) {
        for (int y = 0; y < image.height; ++y) {
            const auto* row = reinterpret_cast<const std::uint32_t*>(image.data + y * image.bytes_per_line);
            std::uint32_t* out = capture.pixels.data() + static_cast<std::size_t>(y) * image.width;
            for (int x = 0; x < image.width; ++x) out[x] = row[x] | 0xff000000u;
        }
        return capture;
    }
    const auto red = mask_shape(image.red_mask), green = mask_shape(image.green_mask),
               blue = mask_shape(image.blue_mask);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const unsigned long pixel = XGetPixel(&image, x, y);
            capture.pixels[static_cast<std::size_t>(y) * image.width + x] =
                0xff000000u | channel_to_8bit(pixel, red) << 16 | channel_to_8bit(pixel, green) << 8 |
                channel_to_8bit(pixel, blue);
        }
    return capture;
}

}  // namespace umf::provider
