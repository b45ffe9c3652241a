#include "shared/detect/image.hpp"

#include <algorithm>
#include <array>
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

void bring_into_cache(const GreyView& im) {
    // Volatile: the reads are the point, and their values are not used.
    constexpr int kLine = 64;
    for (int y = 0; y < im.height; ++y) {
        const volatile std::uint8_t* row = im.row(y);
        for (int x = 0; x < im.width; x += kLine) static_cast<void>(row[x]);
        static_cast<void>(row[im.width - 1]);
    }
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
        for (int x = 0; x < w; ++x)
            q[x] = static_cast<std::uint8_t>((a[2 * x] + a[2 * x + 1] + b[2 * x] + b[2 * x + 1] + 2) >> 2);
    }
    return {out.data(), w, h, w};
}

namespace {

// Keys' cubic weights for the four samples around a point t (0..1) past the
// second of them.
std::array<float, 4> cubic_weights(float t) {
    constexpr float a = -0.75f;
    auto inner = [](float x) { return ((a + 2) * x - (a + 3)) * x * x + 1; };            // |x| <= 1
    auto outer = [](float x) { return ((a * x - 5 * a) * x + 8 * a) * x - 4 * a; };  // 1 < |x| < 2
    return {outer(1 + t), inner(t), inner(1 - t), outer(2 - t)};
}

}  // namespace

GreyView double_size(const GreyView& im, std::vector<std::uint8_t>& out) {
    const int w = 2 * im.width, h = 2 * im.height;
    // Output pixel 2i has its centre a quarter pixel before source pixel i's,
    // 2i + 1 a quarter after: two phases, each a fixed set of four weights.
    const std::array<std::array<float, 4>, 2> phase = {cubic_weights(0.75f), cubic_weights(0.25f)};
    auto clamp_x = [&](int x) { return std::clamp(x, 0, im.width - 1); };
    auto clamp_y = [&](int y) { return std::clamp(y, 0, im.height - 1); };
    // Rows first, into floats at the doubled width; then columns.
    std::vector<float> wide(static_cast<std::size_t>(w) * im.height);
    for (int y = 0; y < im.height; ++y) {
        const std::uint8_t* r = im.row(y);
        float* q = wide.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            const auto& k = phase[x & 1];
            const int base = (x >> 1) - 1 + (x & 1);  // the second of the four samples
            q[x] = k[0] * r[clamp_x(base - 1)] + k[1] * r[clamp_x(base)] + k[2] * r[clamp_x(base + 1)] +
                   k[3] * r[clamp_x(base + 2)];
        }
    }
    out.resize(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        const auto& k = phase[y & 1];
        const int base = (y >> 1) - 1 + (y & 1);
        const float* rows[4];
        for (int j = 0; j < 4; ++j) rows[j] = wide.data() + static_cast<std::size_t>(clamp_y(base - 1 + j)) * w;
        std::uint8_t* q = out.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            const float v = k[0] * rows[0][x] + k[1] * rows[1][x] + k[2] * rows[2][x] + k[3] * rows[3][x];
            q[x] = static_cast<std::uint8_t>(std::clamp(v + 0.5f, 0.0f, 255.0f));
        }
    }
    return {out.data(), w, h, w};
}

namespace {

// Binomial weights of order 8, summing to 256.
constexpr std::array<int, 9> kBinomial8 = {1, 8, 28, 56, 70, 56, 28, 8, 1};

}  // namespace

GreyView smoothed(const GreyView& im, std::vector<std::uint8_t>& out) {
    const int w = im.width, h = im.height;
    constexpr int kReach = 4;
    auto clamp_x = [&](int x) { return std::clamp(x, 0, w - 1); };
    auto clamp_y = [&](int y) { return std::clamp(y, 0, h - 1); };
    // Rows first, kept at 256 times the grey level; then columns.
    std::vector<std::uint16_t> across(static_cast<std::size_t>(w) * h);
    std::vector<int> padded(static_cast<std::size_t>(w) + 2 * kReach);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* r = im.row(y);
        for (int x = -kReach; x < w + kReach; ++x) padded[x + kReach] = r[clamp_x(x)];
        std::uint16_t* q = across.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            int sum = 0;
            for (int k = 0; k < 2 * kReach + 1; ++k) sum += kBinomial8[k] * padded[x + k];
            q[x] = static_cast<std::uint16_t>(sum);
        }
    }
    out.resize(static_cast<std::size_t>(w) * h);
    std::vector<std::uint32_t> sum(w);
    for (int y = 0; y < h; ++y) {
        std::fill(sum.begin(), sum.end(), 0u);
        for (int k = 0; k < 2 * kReach + 1; ++k) {
            const std::uint16_t* r = across.data() + static_cast<std::size_t>(clamp_y(y - kReach + k)) * w;
            for (int x = 0; x < w; ++x) sum[x] += static_cast<std::uint32_t>(kBinomial8[k]) * r[x];
        }
        std::uint8_t* q = out.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) q[x] = static_cast<std::uint8_t>((sum[x] + 32768u) >> 16);
    }
    return {out.data(), w, h, w};
}

}  // namespace umf
