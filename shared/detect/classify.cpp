#include "detect/classify.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umf {

namespace {

// A module's brightness: the median of nine pixels spread over its middle
// half (a 3 x 3 pattern a quarter module apart). Text and thin lines under
// the field darken or brighten a few of them, not the median. NaN when the
// module is not wholly inside the image.
double sample_module(const GreyView& im, const Eigen::Matrix3d& h, double cx, double cy, long& visited) {
    std::uint8_t v[9];
    int n = 0;
    for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b) {
            const Eigen::Vector3d p = h * Eigen::Vector3d(cx + 0.25 * b, cy + 0.25 * a, 1.0);
            if (p.z() <= 0) return std::nan("");
            const int x = static_cast<int>(std::floor(p.x() / p.z())), y = static_cast<int>(std::floor(p.y() / p.z()));
            if (x < 0 || y < 0 || x >= im.width || y >= im.height) return std::nan("");
            v[n++] = im.row(y)[x];
        }
    visited += 9;
    std::nth_element(v, v + 4, v + 9);
    return v[4];
}

// Otsu's threshold over the sampled values.
double otsu(std::vector<double> v, double& low_mean, double& high_mean) {
    std::sort(v.begin(), v.end());
    const int n = static_cast<int>(v.size());
    std::vector<double> prefix(n + 1, 0);
    for (int i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + v[i];
    double best = -1, threshold = v[n / 2];
    for (int i = 1; i < n; ++i) {
        const double m0 = prefix[i] / i, m1 = (prefix[n] - prefix[i]) / (n - i);
        const double between = static_cast<double>(i) * (n - i) * (m1 - m0) * (m1 - m0);
        if (between > best) {
            best = between;
            threshold = (v[i - 1] + v[i]) / 2;
            low_mean = m0;
            high_mean = m1;
        }
    }
    return threshold;
}

}  // namespace

ModuleGrid classify_modules(const GreyView& im, const Eigen::Matrix3d& h, int rows, int cols, int colors,
                            bool edge_key, const ClassifyOptions& o, long& visited) {
    ModuleGrid g(rows, cols);
    std::vector<double> value(static_cast<std::size_t>(rows) * cols, std::nan(""));
    std::vector<double> seen;
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const double v = sample_module(im, h, j + 0.5, i + 0.5, visited);
            value[static_cast<std::size_t>(i) * cols + j] = v;
            if (std::isfinite(v)) seen.push_back(v);
        }
    if (seen.size() < 4) return g;
    double low = 0, high = 0;
    const double threshold = otsu(seen, low, high);
    const double gap = high - low;
    if (!edge_key && colors == 2) {
        // Pictures and text change the brightness under the field, so each
        // module is judged against the modules around it: in a binary field
        // about half of any 5 x 5 block is dark. The global threshold is the
        // fallback where few neighbours were seen.
        constexpr int kRadius = 2;
        for (int i = 0; i < rows; ++i)
            for (int j = 0; j < cols; ++j) {
                const std::size_t k = static_cast<std::size_t>(i) * cols + j;
                const double v = value[k];
                if (!std::isfinite(v)) continue;
                double sum = 0, spread = 0;
                int n = 0;
                for (int a = std::max(0, i - kRadius); a <= std::min(rows - 1, i + kRadius); ++a)
                    for (int b = std::max(0, j - kRadius); b <= std::min(cols - 1, j + kRadius); ++b) {
                        const double w = value[static_cast<std::size_t>(a) * cols + b];
                        if (std::isfinite(w)) sum += w, ++n;
                    }
                double local = threshold, local_gap = gap;
                if (n >= 12) {
                    local = sum / n;
                    for (int a = std::max(0, i - kRadius); a <= std::min(rows - 1, i + kRadius); ++a)
                        for (int b = std::max(0, j - kRadius); b <= std::min(cols - 1, j + kRadius); ++b) {
                            const double w = value[static_cast<std::size_t>(a) * cols + b];
                            if (std::isfinite(w)) spread += std::abs(w - local);
                        }
                    // Two equal clusters sit one mean absolute deviation from their middle.
                    local_gap = 2 * spread / n;
                }
                if (std::abs(v - local) < o.doubt * local_gap) continue;
                g.value[k] = v > local ? 1 : 0;
            }
        g.derive_edges();
        return g;
    }
    // Edge signs from neighbouring centres; a step of a small fraction of the
    // brightness range counts as flat.
    const double flat = o.flat_step * gap / std::max(1, colors - 1);
    auto sign_of = [&](double a, double b) -> std::int8_t {
        if (!std::isfinite(a) || !std::isfinite(b)) return ModuleGrid::kUnknown;
        const double d = b - a;
        if (std::abs(d) < flat) return 0;
        return d > 0 ? 1 : -1;
    };
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const double v = value[static_cast<std::size_t>(i) * cols + j];
            if (j + 1 < cols) g.right_of(i, j) = sign_of(v, value[static_cast<std::size_t>(i) * cols + j + 1]);
            if (i + 1 < rows) g.below(i, j) = sign_of(v, value[static_cast<std::size_t>(i + 1) * cols + j]);
        }
    return g;
}

}  // namespace umf
