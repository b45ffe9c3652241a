#include "detect/image.hpp"

#include <stdexcept>

namespace umf {

std::string describe_invalid(const GreyView& im) {
    if (!im.data) return "no pixel data";
    if (im.width <= 0 || im.height <= 0) return "empty image";
    if (im.width > kMaxImageSideForDetection || im.height > kMaxImageSideForDetection)
        return "image of " + std::to_string(im.width) + " x " + std::to_string(im.height) +
               " is larger than the limit of " + std::to_string(kMaxImageSideForDetection) + " a side";
    if (im.stride < im.width) return "stride " + std::to_string(im.stride) + " is smaller than the width";
    return {};
}

namespace {

int channels_of(PixelOrder order) { return order == PixelOrder::rgb || order == PixelOrder::bgr ? 3 : 4; }

}  // namespace

std::string describe_invalid(const ColourView& im) {
    // The checks of a grey view, with the row's bytes counted in pixels.
    const std::ptrdiff_t pixels_per_stride = im.stride / channels_of(im.order);
    return describe_invalid(GreyView{im.data, im.width, im.height, pixels_per_stride});
}

GreyView to_luma(const ColourView& im, std::vector<std::uint8_t>& out) {
    const int channels = channels_of(im.order);
    if (auto problem = describe_invalid(im); !problem.empty())
        throw std::invalid_argument("to_luma: " + problem);
    const bool red_first = im.order == PixelOrder::rgb || im.order == PixelOrder::rgba;
    out.resize(static_cast<std::size_t>(im.width) * im.height);
    for (int y = 0; y < im.height; ++y) {
        const std::uint8_t* p = im.data + y * im.stride;
        std::uint8_t* q = out.data() + static_cast<std::size_t>(y) * im.width;
        for (int x = 0; x < im.width; ++x, p += channels) {
            const int r = red_first ? p[0] : p[2], g = p[1], b = red_first ? p[2] : p[0];
            q[x] = static_cast<std::uint8_t>((77 * r + 150 * g + 29 * b + 128) >> 8);
        }
    }
    return {out.data(), im.width, im.height, im.width};
}

GreyView half_size(const GreyView& im, std::vector<std::uint8_t>& out) {
    const int w = im.width / 2, h = im.height / 2;
    out.resize(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* a = im.row(2 * y);
        const std::uint8_t* b = im.row(2 * y + 1);
        std::uint8_t* q = out.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) q[x] = static_cast<std::uint8_t>((a[2 * x] + a[2 * x + 1] + b[2 * x] + b[2 * x + 1] + 2) >> 2);
    }
    return {out.data(), w, h, w};
}

}  // namespace umf
