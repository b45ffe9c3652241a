#include "shared/detect/classify.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <vector>

namespace umf {

namespace {

constexpr double kUnread = std::numeric_limits<double>::quiet_NaN();  // a module not wholly in view

// The medians of nine values, for a row of `n` modules at once: `p` holds
// the first value of each module, then the second, ... (n apart). Paeth's
// network of 19 exchanges, each one over the whole row: no branches, and
// loops the compiler vectorises, for the millions of modules read a second.
// The medians end where the fifth values were.
void medians_of_9(std::uint8_t* p, int n) {
    auto sort2 = [p, n](int a, int b) {
        std::uint8_t* __restrict x = p + static_cast<std::ptrdiff_t>(a) * n;
        std::uint8_t* __restrict y = p + static_cast<std::ptrdiff_t>(b) * n;
        for (int j = 0; j < n; ++j) {
            const std::uint8_t lo = std::min(x[j], y[j]), hi = std::max(x[j], y[j]);
            x[j] = lo;
            y[j] = hi;
        }
    };
    sort2(1, 2), sort2(4, 5), sort2(7, 8), sort2(0, 1), sort2(3, 4), sort2(6, 7), sort2(1, 2), sort2(4, 5);
    sort2(7, 8), sort2(0, 3), sort2(5, 8), sort2(4, 7), sort2(3, 6), sort2(1, 4), sort2(2, 5), sort2(4, 7);
    sort2(4, 2), sort2(6, 4), sort2(4, 2);
}

// A module's nine pixels, spread over its middle half (a 3 x 3 pattern a
// quarter module apart), whose median is its brightness: text and thin
// lines under the field darken or brighten a few of them, not the median.
// Written `stride` apart from `v`; false when the module is not wholly
// inside the image. `c` is the module's centre under the grid's homography
// h (homogeneous), `qx` and `qy` a quarter module along each axis (h's
// first and second columns over 4).
bool sample_module(const GreyView& im, const Eigen::Vector3d& c, const Eigen::Vector3d& qx, const Eigen::Vector3d& qy,
                   std::uint8_t* v, int stride) {
    // The module is small enough for the homography to be affine across it:
    // a quarter module along each axis from its centre, step from there.
    if (c.z() <= 0) return false;
    const Eigen::Vector3d ex = c + qx, ey = c + qy;
    const double px = c.x() / c.z(), py = c.y() / c.z();
    const double dxx = ex.x() / ex.z() - px, dxy = ex.y() / ex.z() - py;
    const double dyx = ey.x() / ey.z() - px, dyy = ey.y() / ey.z() - py;
    // The nine pixels lie within the centre's reach of |dx| + |dy|.
    const double reach = std::abs(dxx) + std::abs(dyx) + std::abs(dxy) + std::abs(dyy);
    if (px - reach < 0 || py - reach < 0 || px + reach >= im.width || py + reach >= im.height) return false;
    int n = 0;
    for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b) {
            const int x = static_cast<int>(px + b * dxx + a * dyx), y = static_cast<int>(py + b * dxy + a * dyy);
            v[static_cast<std::ptrdiff_t>(n++) * stride] = im.row(y)[x];
        }
    return true;
}

// The values in ascending order. They are medians of pixels, whole grey
// levels, so counted rather than compared.
void sort_grey_levels(std::vector<double>& v) {
    std::array<int, 256> count{};
    for (double x : v) ++count[static_cast<std::uint8_t>(x)];
    std::size_t at = 0;
    for (int level = 0; level < 256; ++level)
        for (int c = 0; c < count[level]; ++c) v[at++] = level;
}

// Otsu's threshold over the sampled values.
double otsu(std::vector<double> v, double& low_mean, double& high_mean) {
    sort_grey_levels(v);
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


// The field's step between a dark and a light module over the same
// content, as the image shows it: adjacent modules either read alike or
// differ by it, and only a few pairs straddle a change of the content
// (a card's border, a picture's edge), so it is the upper quarter of the
// differences between neighbours. 0 when too few pairs were seen.
double field_step(const std::vector<double>& value, int rows, int cols) {
    std::vector<double> d;
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const double v = value[static_cast<std::size_t>(i) * cols + j];
            if (!std::isfinite(v)) continue;
            if (j + 1 < cols && std::isfinite(value[static_cast<std::size_t>(i) * cols + j + 1]))
                d.push_back(std::abs(value[static_cast<std::size_t>(i) * cols + j + 1] - v));
            if (i + 1 < rows && std::isfinite(value[static_cast<std::size_t>(i + 1) * cols + j]))
                d.push_back(std::abs(value[static_cast<std::size_t>(i + 1) * cols + j] - v));
        }
    if (d.size() < 8) return 0;
    // The (3/4 size)-th smallest; differences of grey levels, so counted.
    std::array<int, 256> count{};
    for (double x : d) ++count[static_cast<std::uint8_t>(x)];
    const std::size_t q = d.size() * 3 / 4;
    std::size_t below = 0;
    for (int level = 0; level < 256; ++level) {
        below += static_cast<std::size_t>(count[level]);
        if (below > q) return level;
    }
    return 255;
}

// To each module's sums of the levels near its own (within `within`), their
// squares and their count, the level at one offset: `levels` (and their
// `squares`) from that offset on, `centre` the modules' own levels, all
// `cols` long.
void add_near(const int* __restrict levels, const int* __restrict squares, const int* __restrict centre, int within,
              int cols, int* __restrict sum, int* __restrict sq, int* __restrict n) {
    for (int j = 0; j < cols; ++j) {
        const int u = levels[j];
        const int near = -static_cast<int>(std::abs(u - centre[j]) <= within);  // all ones or zero
        sum[j] += u & near;
        sq[j] += squares[j] & near;
        n[j] -= near;
    }
}

// Binary modules, each judged against the modules around it that lie over
// the same content: pictures, text and cards change the brightness under
// the field, and in a binary field about half of any 5 x 5 block is dark.
// Neighbours farther from a module's value than the field's step can
// explain lie over other content (across a card's border) and are left
// out, so the threshold does not fall between two backgrounds. The global
// threshold is the fallback where too few neighbours are left.
void classify_binary(const std::vector<double>& value, int rows, int cols, double threshold, double gap,
                     const ClassifyOptions& o, ModuleGrid& g) {
    constexpr int kRadius = 2;
    const double step = field_step(value, rows, cols);
    // A field step read under another tone curve or gain, and noise, stay within this.
    const double reach = 1.6 * step;
    // The values are whole grey levels: as integers, with a border of
    // unread ones, they sum exactly in any order. An unread module, and
    // with a step any module further than it reaches, is left out by the
    // one test |u - v| > within (grey levels differ by at most 255).
    constexpr int kUnreadLevel = 1 << 14;
    const int within = step > 0 ? static_cast<int>(std::floor(reach)) : 255;
    const int padded_cols = cols + 2 * kRadius;
    std::vector<int> level(static_cast<std::size_t>(rows + 2 * kRadius) * padded_cols, kUnreadLevel);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const double v = value[static_cast<std::size_t>(i) * cols + j];
            if (std::isfinite(v))
                level[static_cast<std::size_t>(i + kRadius) * padded_cols + j + kRadius] = static_cast<int>(v);
        }
    std::vector<int> square(level.size());
    for (std::size_t k = 0; k < level.size(); ++k) square[k] = level[k] * level[k];
    // Each row's sums at once, one neighbour offset after the other: the
    // same additions as module by module, in loops the compiler vectorises.
    // An unread centre's sentinel is further than `within` from every level.
    constexpr int kNoCentre = -(1 << 20);
    std::vector<int> centre(static_cast<std::size_t>(cols)), sum(centre.size()), sq(centre.size()), n(centre.size());
    for (int i = 0; i < rows; ++i) {
        const int* own = &level[static_cast<std::size_t>(i + kRadius) * padded_cols + kRadius];
        for (int j = 0; j < cols; ++j) centre[j] = own[j] == kUnreadLevel ? kNoCentre : own[j];
        std::fill(sum.begin(), sum.end(), 0);
        std::fill(sq.begin(), sq.end(), 0);
        std::fill(n.begin(), n.end(), 0);
        for (int a = 0; a <= 2 * kRadius; ++a)
            for (int b = 0; b <= 2 * kRadius; ++b)
                add_near(&level[static_cast<std::size_t>(i + a) * padded_cols + b],
                         &square[static_cast<std::size_t>(i + a) * padded_cols + b], centre.data(), within, cols,
                         sum.data(), sq.data(), n.data());
        for (int j = 0; j < cols; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * cols + j;
            const double v = value[k];
            if (!std::isfinite(v)) continue;
            double local = threshold, local_gap = gap;
            if (n[j] >= 8) {
                local = static_cast<double>(sum[j]) / n[j];
                const double var = std::max(0.0, static_cast<double>(sq[j]) / n[j] - local * local);
                // Two equal clusters sit one standard deviation from their middle.
                local_gap = 2 * std::sqrt(var);
            }
            if (std::abs(v - local) < o.doubt * local_gap) continue;
            g.value[k] = v > local ? 1 : 0;
        }
    }
}

}  // namespace

ModuleGrid classify_modules(const GreyView& im, const Eigen::Matrix3d& h, int rows, int cols, int colors,
                            bool edge_key, const ClassifyOptions& o, long& visited) {
    ModuleGrid g(rows, cols);
    std::vector<double> value(static_cast<std::size_t>(rows) * cols, kUnread);
    std::vector<double> seen;
    // A quarter module along each axis is the same step everywhere in homogeneous coordinates.
    const Eigen::Vector3d qx = 0.25 * h.col(0), qy = 0.25 * h.col(1);
    // A row of modules at a time: their pixels, then their medians.
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(cols) * 9);
    std::vector<char> inside(static_cast<std::size_t>(cols));
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const Eigen::Vector3d c = h * Eigen::Vector3d(j + 0.5, i + 0.5, 1.0);
            inside[j] = sample_module(im, c, qx, qy, &pixels[j], cols);  // outside: whatever was there, unused
        }
        medians_of_9(pixels.data(), cols);
        const std::uint8_t* median = pixels.data() + static_cast<std::size_t>(4) * cols;
        for (int j = 0; j < cols; ++j) {
            if (!inside[j]) continue;
            visited += 9;
            value[static_cast<std::size_t>(i) * cols + j] = median[j];
            seen.push_back(median[j]);
        }
    }
    if (seen.size() < 4) return g;
    double low = 0, high = 0;
    const double threshold = otsu(seen, low, high);
    const double gap = high - low;
    if (!edge_key && colors == 2) {
        classify_binary(value, rows, cols, threshold, gap, o, g);
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
