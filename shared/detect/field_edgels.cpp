#include "shared/detect/field_edgels.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace umf {

namespace {

constexpr int kBinsPerOctave = 4;
constexpr int kBins = 8 * kBinsPerOctave;  // steps of 1 to 256 grey levels

// floor(log2(step) * kBinsPerOctave), clamped to the bins: the octave from
// the exponent, the quarter from the mantissa (no logarithm; this runs on
// every edgel of a scan).
int bin_of(double step) {
    static const double kQuarter[3] = {std::exp2(0.25), std::exp2(0.5), std::exp2(0.75)};
    int octave = 0;
    const double mantissa = 2 * std::frexp(std::max(step, 1.0), &octave);  // in [1, 2)
    const int quarter = (mantissa >= kQuarter[0]) + (mantissa >= kQuarter[1]) + (mantissa >= kQuarter[2]);
    return std::min((octave - 1) * kBinsPerOctave + quarter, kBins - 1);
}

}  // namespace

double commonest_edge_step(const std::vector<Edgel>& edgels) {
    if (edgels.size() < 40) return 0;
    std::array<int, kBins> count{};
    for (const Edgel& e : edgels) ++count[static_cast<std::size_t>(bin_of(e.step))];
    // A bin with its neighbours: a peak that straddles two bins still wins.
    int best = 0;
    long best_sum = -1;
    for (int b = 0; b < kBins; ++b) {
        const long sum = 2L * count[static_cast<std::size_t>(b)] + (b > 0 ? count[static_cast<std::size_t>(b - 1)] : 0) +
                         (b + 1 < kBins ? count[static_cast<std::size_t>(b + 1)] : 0);
        if (sum > best_sum) {
            best_sum = sum;
            best = b;
        }
    }
    return std::exp2((best + 0.5) / kBinsPerOctave);
}

std::vector<Edgel> edgels_stepping_by(const std::vector<Edgel>& edgels, double step, double spread) {
    std::vector<Edgel> out;
    if (step <= 0) return out;
    const double low = step / spread, high = step * spread;
    for (const Edgel& e : edgels)
        if (e.step >= low && e.step <= high) out.push_back(e);
    return out;
}

bool modules_look_small(const std::vector<Edgel>& edgels) {
    constexpr int kSmallModulePx = 5, kLongestGapPx = 40, kFewestGaps = 100;
    const double step = commonest_edge_step(edgels);
    if (step <= 0) return false;
    // As edgels_stepping_by would keep them, without the copy.
    const double low = step / 2, high = step * 2;
    std::array<int, kLongestGapPx + 1> count{};
    int gaps = 0;
    const Edgel* a = nullptr;
    for (const Edgel& b : edgels) {
        if (!(b.step >= low && b.step <= high)) continue;
        if (a && a->on_row == b.on_row && (a->on_row ? a->y == b.y : a->x == b.x)) {
            const long gap = std::lround(a->on_row ? b.x - a->x : b.y - a->y);
            if (gap > 0) {
                ++count[static_cast<std::size_t>(std::min<long>(gap, kLongestGapPx))];
                ++gaps;
            }
        }
        a = &b;
    }
    if (gaps < kFewestGaps) return false;
    const auto commonest = std::max_element(count.begin() + 1, count.end());
    return commonest - count.begin() <= kSmallModulePx && 4 * *commonest >= gaps;
}

std::vector<Edgel> edgels_off_thin_lines(const std::vector<Edgel>& edgels, double max_width_px) {
    const std::size_t n = edgels.size();
    std::vector<char> thin(n, 0);
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const Edgel &a = edgels[k], &b = edgels[k + 1];
        if (a.on_row != b.on_row) continue;
        // Along the scanline: position and the gradient's sign there.
        const float across_a = a.on_row ? a.y : a.x, across_b = b.on_row ? b.y : b.x;
        const float at_a = a.on_row ? a.x : a.y, at_b = b.on_row ? b.x : b.y;
        const float ga = a.on_row ? a.gx : a.gy, gb = b.on_row ? b.gx : b.gy;
        if (across_a != across_b || at_b - at_a > max_width_px || (ga > 0) == (gb > 0)) continue;
        if (std::max(a.step, b.step) > 2 * std::min(a.step, b.step)) continue;
        thin[k] = thin[k + 1] = 1;
    }
    std::vector<Edgel> out;
    out.reserve(n);
    for (std::size_t k = 0; k < n; ++k)
        if (!thin[k]) out.push_back(edgels[k]);
    return out;
}

}  // namespace umf
