#include "shared/detect/field_edgels.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace umf {

namespace {

constexpr int kBinsPerOctave = 4;
constexpr int kBins = 8 * kBinsPerOctave;  // steps of 1 to 256 grey levels

int bin_of(double step) {
    return std::clamp(static_cast<int>(std::floor(std::log2(std::max(step, 1.0)) * kBinsPerOctave)), 0, kBins - 1);
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
