#include "provider/tuning/palette_from_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_map>

namespace umf::provider {

namespace {

// Pixels are binned at 5 bits per channel: k-means then runs over at most
// 32768 bins instead of millions of pixels, while each bin keeps the sum of
// its exact colours so a flat colour comes back exactly.
struct Bin {
    double weight = 0.0;
    std::array<double, 3> sum{};
    std::array<double, 3> mean() const { return {sum[0] / weight, sum[1] / weight, sum[2] / weight}; }
};

double distance2(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c) d += (a[c] - b[c]) * (a[c] - b[c]);
    return d;
}

double luma(const std::array<double, 3>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

std::string hex(const std::array<double, 3>& c) {
    auto byte = [](double v) { return static_cast<int>(std::clamp(std::lround(v), 0L, 255L)); };
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(c[0]), byte(c[1]), byte(c[2]));
    return buf;
}

std::vector<Bin> histogram(const QImage& image) {
    const QImage argb = image.convertToFormat(QImage::Format_ARGB32);
    // A screen is millions of pixels; a few hundred thousand say as much
    // about which colours dominate.
    const long pixels = static_cast<long>(argb.width()) * argb.height();
    const int step = std::max(1, static_cast<int>(std::sqrt(pixels / 250000.0)));
    std::unordered_map<int, Bin> bins;
    for (int y = 0; y < argb.height(); y += step) {
        const auto* row = reinterpret_cast<const QRgb*>(argb.constScanLine(y));
        for (int x = 0; x < argb.width(); x += step) {
            const QRgb p = row[x];
            if (qAlpha(p) < 128) continue;
            const int r = qRed(p), g = qGreen(p), b = qBlue(p);
            Bin& bin = bins[(r >> 3) << 10 | (g >> 3) << 5 | (b >> 3)];
            bin.weight += 1.0;
            bin.sum[0] += r;
            bin.sum[1] += g;
            bin.sum[2] += b;
        }
    }
    std::vector<std::pair<int, Bin>> sorted(bins.begin(), bins.end());
    // Sorted by key so the result does not depend on hash order.
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Bin> out;
    out.reserve(sorted.size());
    for (auto& [key, bin] : sorted) out.push_back(bin);
    return out;
}

}  // namespace

std::vector<std::string> palette_from_image(const QImage& image, int colours) {
    if (colours < 1 || image.isNull()) return {};
    const std::vector<Bin> bins = histogram(image);
    if (bins.empty()) return {};
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(colours), bins.size());

    // Farthest-first seeding weighted by the bin's share: the next seed is
    // the colour both common and far from every seed so far.
    std::vector<std::array<double, 3>> centres;
    std::size_t heaviest = 0;
    for (std::size_t i = 1; i < bins.size(); ++i)
        if (bins[i].weight > bins[heaviest].weight) heaviest = i;
    centres.push_back(bins[heaviest].mean());
    std::vector<double> nearest(bins.size(), std::numeric_limits<double>::infinity());
    while (centres.size() < k) {
        std::size_t best = 0;
        double best_score = -1.0;
        for (std::size_t i = 0; i < bins.size(); ++i) {
            nearest[i] = std::min(nearest[i], distance2(bins[i].mean(), centres.back()));
            const double score = bins[i].weight * nearest[i];
            if (score > best_score) best_score = score, best = i;
        }
        if (best_score <= 0.0) break;  // every bin sits on a centre already
        centres.push_back(bins[best].mean());
    }

    std::vector<std::size_t> owner(bins.size(), 0);
    for (int iteration = 0; iteration < 30; ++iteration) {
        bool moved = false;
        for (std::size_t i = 0; i < bins.size(); ++i) {
            const auto m = bins[i].mean();
            std::size_t best = 0;
            for (std::size_t c = 1; c < centres.size(); ++c)
                if (distance2(m, centres[c]) < distance2(m, centres[best])) best = c;
            if (best != owner[i]) owner[i] = best, moved = true;
        }
        std::vector<Bin> sums(centres.size());
        for (std::size_t i = 0; i < bins.size(); ++i) {
            Bin& s = sums[owner[i]];
            s.weight += bins[i].weight;
            for (int c = 0; c < 3; ++c) s.sum[c] += bins[i].sum[c];
        }
        for (std::size_t c = 0; c < centres.size(); ++c)
            if (sums[c].weight > 0.0) centres[c] = sums[c].mean();
        if (!moved && iteration > 0) break;  // the first pass must recentre even when nothing moved
    }

    std::sort(centres.begin(), centres.end(), [](const auto& a, const auto& b) { return luma(a) < luma(b); });
    std::vector<std::string> out;
    for (const auto& c : centres) {
        std::string h = hex(c);
        if (std::find(out.begin(), out.end(), h) == out.end()) out.push_back(std::move(h));
    }
    return out;
}

}  // namespace umf::provider
