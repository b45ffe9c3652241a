#include "shared/detect/edgels.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace umf {

namespace {

// The lower quartile of |v[0..n)| (the element nth_element puts at n / 4).
// Counted in a histogram of the small values that noise makes; sorted in
// part only when the quartile lies beyond them (a line all edges).
int lower_quartile(const int* v, int n, std::vector<int>& scratch) {
    constexpr int kSmall = 256;
    int counts[kSmall] = {};
    for (int i = 0; i < n; ++i) {
        const int a = std::abs(v[i]);
        if (a < kSmall) ++counts[a];
    }
    const int k = n / 4;
    for (int value = 0, below = 0; value < kSmall; ++value) {
        below += counts[value];
        if (below > k) return value;
    }
    scratch.resize(n);
    for (int i = 0; i < n; ++i) scratch[i] = std::abs(v[i]);
    std::nth_element(scratch.begin(), scratch.begin() + k, scratch.end());
    return scratch[k];
}

// Edges along one line of samples s[0..n): peaks of the smoothed derivative
// d[i] = s[i+1] + s[i+2] - s[i-1] - s[i-2] that stand out of the line's noise
// (a robust estimate from the lower quartile of |d|) by `deviations` and reach
// the contrast floor. Calls found(position, step) with a sub-pixel position
// and the grey levels across the edge.
template <typename Sample, typename Found>
double scan_line(int n, Sample s, int floor, double deviations, std::vector<int>& d, std::vector<int>& scratch,
                 Found found) {
    if (n < 7) return 0;
    d.assign(n, 0);
    for (int i = 2; i + 2 < n; ++i) d[i] = (s(i + 1) + s(i + 2)) - (s(i - 1) + s(i - 2));
    // The noise's standard deviation from the lower quartile of |d|
    // (3.14 * quartile for Gaussian noise): where modules are small and
    // blurred, edges spread over most of a line and would inflate a median.
    const double sigma_d = 3.14 * lower_quartile(d.data() + 2, n - 4, scratch);
    const double threshold = std::max(2.0 * floor, deviations * sigma_d);
    int prev = std::abs(d[2]), cur = std::abs(d[3]);
    for (int i = 3; i + 3 < n; ++i) {
        const int next = std::abs(d[i + 1]);
        if (cur >= threshold && cur >= prev && cur > next) {
            // A parabola through the three magnitudes places the peak.
            const double den = prev - 2.0 * cur + next;
            const double off = den != 0 ? 0.5 * (prev - next) / den : 0.0;
            found(i + std::clamp(off, -0.5, 0.5), cur / 2.0);
        }
        prev = cur;
        cur = next;
    }
    return sigma_d / 2;  // d sums four pixels: twice a pixel's deviation
}

}  // namespace

int scanline_step(int width, int height, const EdgelOptions& o) {
    return o.step > 0 ? o.step : std::max(4, std::max(width, height) / 40);
}

EdgelScan find_edgels(const GreyView& im, const EdgelOptions& o) {
    EdgelScan out;
    if (!describe_invalid(im).empty() || im.width < 8 || im.height < 8) return out;
    out.step = scanline_step(im.width, im.height, o);
    const int thr = std::max(1, o.min_contrast);
    std::vector<int> d, scratch;
    std::vector<double> noise;
    auto keep = [&](float x, float y, bool on_row, double step) {
        const int xi = std::clamp(static_cast<int>(std::lround(x)), 1, im.width - 2);
        const int yi = std::clamp(static_cast<int>(std::lround(y)), 1, im.height - 2);
        Edgel e;
        e.x = x + 0.5f;  // pixel i covers [i, i+1): its centre is i + 0.5
        e.y = y + 0.5f;
        e.on_row = on_row;
        e.step = static_cast<float>(step);
        sobel(im, xi, yi, e.gx, e.gy);
        out.pixels_visited += 9;
        out.edgels.push_back(e);
    };
    const int first = o.offset >= 0 ? o.offset : out.step / 2;
    const int half = std::clamp(o.across, 1, 5) / 2;
    // Sums over the pixels across the line: a step grows n times, the noise
    // sqrt(n) times; steps are reported per pixel again, and the noise as a
    // single pixel's (the Sobel gradients are of single pixels).
    const int n_across = 2 * half + 1;
    std::vector<int> line;
    for (int y = std::max(first, half); y + half < im.height; y += out.step) {
        line.assign(im.width, 0);
        for (int dy = -half; dy <= half; ++dy) {
            const std::uint8_t* row = im.row(y + dy);
            for (int i = 0; i < im.width; ++i) line[i] += row[i];
        }
        out.pixels_visited += static_cast<long>(im.width) * n_across;
        noise.push_back(scan_line(im.width, [&line](int i) { return line[i]; }, thr * n_across, o.noise_deviations, d,
                                  scratch,
                                  [&](double x, double step) {
                                      keep(static_cast<float>(x), static_cast<float>(y), true, step / n_across);
                                  }) / std::sqrt(n_across));
    }
    for (int x = std::max(first, half); x + half < im.width; x += out.step) {
        line.assign(im.height, 0);
        for (int i = 0; i < im.height; ++i) {
            const std::uint8_t* row = im.row(i);
            for (int dx = -half; dx <= half; ++dx) line[i] += row[x + dx];
        }
        out.pixels_visited += static_cast<long>(im.height) * n_across;
        noise.push_back(scan_line(im.height, [&line](int i) { return line[i]; }, thr * n_across, o.noise_deviations, d,
                                  scratch,
                                  [&](double y, double step) {
                                      keep(static_cast<float>(x), static_cast<float>(y), false, step / n_across);
                                  }) / std::sqrt(n_across));
    }
    if (!noise.empty()) {
        std::nth_element(noise.begin(), noise.begin() + noise.size() / 2, noise.end());
        out.noise_sigma = noise[noise.size() / 2];
    }
    return out;
}

}  // namespace umf
