#include "tests/sim/pixel_structure.hpp"

#include <cmath>

namespace umf::sim {
namespace {

// Inside [lo, hi) of a cell [0, 1) with a centred emitter of the given fill.
bool in_emitter(double t, double fill) { return std::abs(t - 0.5) < 0.5 * fill; }

double frac(double v) { return v - std::floor(v); }

// LCD stripes: three columns per pixel, R left (channel 2), then G, then B.
// Each emitter covers fill x fill of its column's cell; the gain inside is
// 3 / fill^2 (its share of the pixel is fill^2 / 3).
float stripe(const PixelStructure& s, cv::Point2d p, int channel) {
    const double fx = frac(p.x) * 3, fy = frac(p.y);
    const int column = static_cast<int>(fx);
    const int wanted = 2 - channel;  // column 0 is red = channel 2
    if (column != wanted || !in_emitter(frac(fx), s.fill) || !in_emitter(fy, s.fill)) return 0;
    return static_cast<float>(3 / (s.fill * s.fill));
}

// OLED diamond (RGBG): each pixel's left half holds a green emitter, the
// right half a red one on even pixels (x + y even) and a blue one on odd
// ones. Green covers the same share in every pixel; red and blue each light
// only half of the pixels, so their gain is twice as high where they are.
// Green emitters are smaller than red and blue, as on real panels.
float pentile(const PixelStructure& s, cv::Point2d p, int channel) {
    const double fx = frac(p.x) * 2, fy = frac(p.y);
    const int half = static_cast<int>(fx);
    const bool even = ((static_cast<long long>(std::floor(p.x)) + static_cast<long long>(std::floor(p.y))) & 1) == 0;
    const double green_fill = 0.75 * s.fill;
    if (half == 0) {
        if (channel != 1 || !in_emitter(frac(fx), green_fill) || !in_emitter(fy, green_fill)) return 0;
        return static_cast<float>(2 / (green_fill * green_fill));
    }
    const int here = even ? 2 : 0;
    if (channel != here || !in_emitter(frac(fx), s.fill) || !in_emitter(fy, s.fill)) return 0;
    return static_cast<float>(4 / (s.fill * s.fill));
}

}  // namespace

const char* to_string(PixelLayout layout) {
    switch (layout) {
    case PixelLayout::rgb_stripe: return "rgb_stripe";
    case PixelLayout::pentile: return "pentile";
    }
    return "?";
}

float structure_emission(const PixelStructure& s, cv::Point2d screen_px, int channel) {
    return s.layout == PixelLayout::pentile ? pentile(s, screen_px, channel) : stripe(s, screen_px, channel);
}

cv::Mat structure_gain(const PixelStructure& s, const cv::Matx33d& h, cv::Size image) {
    CV_Assert(s.samples >= 1 && s.fill > 0 && s.fill <= 1);
    cv::Mat gain(image, CV_32FC3);
    const int n = s.samples;
    const float weight = 1.0f / static_cast<float>(n * n);
    cv::parallel_for_(cv::Range(0, image.height), [&](const cv::Range& rows) {
        for (int y = rows.start; y < rows.end; ++y) {
            auto* out = gain.ptr<cv::Vec3f>(y);
            for (int x = 0; x < image.width; ++x) {
                cv::Vec3f sum(0, 0, 0);
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) {
                        const double ix = x + (i + 0.5) / n, iy = y + (j + 0.5) / n;
                        const double w = h(2, 0) * ix + h(2, 1) * iy + h(2, 2);
                        if (w <= 0) continue;
                        const cv::Point2d p((h(0, 0) * ix + h(0, 1) * iy + h(0, 2)) / w,
                                            (h(1, 0) * ix + h(1, 1) * iy + h(1, 2)) / w);
                        for (int c = 0; c < 3; ++c) sum[c] += structure_emission(s, p, c);
                    }
                out[x] = sum * weight;
            }
        }
    });
    return gain;
}

}  // namespace umf::sim
