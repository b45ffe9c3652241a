#include "shared/detect/lattice.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "shared/detect/fft.hpp"

namespace umf {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Sobel magnitude over the n x n patch at (x0, y0), which lies a pixel
// inside the image, its mean removed and a Hann window applied (no edge of
// the patch makes a line in the spectrum).
std::vector<double> edge_strength(const GreyView& im, int x0, int y0, int n) {
    std::vector<double> e(static_cast<std::size_t>(n) * n, 0.0);
    double sum = 0;
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            float gx, gy;
            sobel(im, x0 + x, y0 + y, gx, gy);
            const double m = std::hypot(static_cast<double>(gx), static_cast<double>(gy));
            e[static_cast<std::size_t>(y) * n + x] = m;
            sum += m;
        }
    }
    const double mean = sum / static_cast<double>(e.size());
    std::vector<double> hann(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) hann[static_cast<std::size_t>(i)] = 0.5 - 0.5 * std::cos(kTwoPi * i / n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            double& v = e[static_cast<std::size_t>(y) * n + x];
            v = (v - mean) * hann[static_cast<std::size_t>(y)] * hann[static_cast<std::size_t>(x)];
        }
    return e;
}

struct Peak {
    double magnitude;
    int kx, ky;  // cycles over the patch; ky may be negative, kx >= 0 (one half of the symmetric spectrum)
};

// Local maxima of the magnitude over the half plane, in the band of the
// module sizes looked for, strongest first; only those standing well above
// the band's mean (a flat or noisy patch has none).
std::vector<Peak> spectral_peaks(const std::vector<double>& e, int n, const LatticeOptions& o) {
    std::vector<Complex> s(e.begin(), e.end());
    fft_2d(s, n);
    std::vector<double> magnitude(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) magnitude[i] = std::sqrt(std::norm(s[i]));
    const auto mag = [&](int kx, int ky) {
        return magnitude[static_cast<std::size_t>(((ky % n) + n) % n) * n + static_cast<std::size_t>(((kx % n) + n) % n)];
    };
    const double r_lo = n / o.max_period_px, r_hi = n / o.min_period_px;
    std::vector<Peak> peaks;
    double band_sum = 0;
    int band_bins = 0;
    for (int ky = -n / 2 + 1; ky < n / 2; ++ky)
        for (int kx = 0; kx < n / 2; ++kx) {
            if (kx == 0 && ky <= 0) continue;
            const double r = std::hypot(kx, ky);
            if (r < r_lo || r > r_hi) continue;
            const double m = mag(kx, ky);
            band_sum += m;
            ++band_bins;
            bool peak = true;
            for (int dy = -1; dy <= 1 && peak; ++dy)
                for (int dx = -1; dx <= 1 && peak; ++dx)
                    if ((dx || dy) && mag(kx + dx, ky + dy) > m) peak = false;
            if (peak) peaks.push_back({m, kx, ky});
        }
    const double floor = o.min_peak_to_mean * band_sum / std::max(1, band_bins);
    peaks.erase(std::remove_if(peaks.begin(), peaks.end(), [&](const Peak& p) { return !(p.magnitude > floor); }),
                peaks.end());
    std::sort(peaks.begin(), peaks.end(), [](const Peak& a, const Peak& b) { return a.magnitude > b.magnitude; });
    return peaks;
}

// The patch's Fourier coefficient at frequency f (cycles per pixel), from
// separable phasors: n^2 multiply-adds.
Complex coefficient(const std::vector<double>& e, int n, const Eigen::Vector2d& f) {
    std::vector<Complex> ex(static_cast<std::size_t>(n)), ey(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        ex[static_cast<std::size_t>(i)] = std::polar(1.0, -kTwoPi * f.x() * i);
        ey[static_cast<std::size_t>(i)] = std::polar(1.0, -kTwoPi * f.y() * i);
    }
    Complex total = 0;
    for (int y = 0; y < n; ++y) {
        Complex row = 0;
        const double* line = e.data() + static_cast<std::ptrdiff_t>(y) * n;
        for (int x = 0; x < n; ++x) row += line[x] * ex[static_cast<std::size_t>(x)];
        total += row * ey[static_cast<std::size_t>(y)];
    }
    return total;
}

// The peak's frequency to a 16th of a bin, by a search over halving steps:
// a whole bin (1/n cycle per pixel) off would move the lines at the patch's
// edges by half a module, a 32nd of one by a 64th.
Eigen::Vector2d refine_frequency(const std::vector<double>& e, int n, const Peak& p) {
    Eigen::Vector2d f(static_cast<double>(p.kx) / n, static_cast<double>(p.ky) / n);
    double best = std::abs(coefficient(e, n, f));
    for (double step = 0.25 / n; step > 0.05 / n; step /= 2) {
        for (bool moved = true; moved;) {
            moved = false;
            for (const Eigen::Vector2d& d : {Eigen::Vector2d(step, 0), Eigen::Vector2d(-step, 0), Eigen::Vector2d(0, step),
                                            Eigen::Vector2d(0, -step)}) {
                const double m = std::abs(coefficient(e, n, f + d));
                if (m > best) {
                    best = m;
                    f += d;
                    moved = true;
                }
            }
        }
    }
    return f;
}

// The partner of the first peak: the strongest one at an angle to it, with
// a spacing not too far from its own (its harmonics and the content's
// coarser periods are not).
const Peak* partner(const std::vector<Peak>& peaks, const Peak& first, const LatticeOptions& o) {
    const double a1 = std::atan2(first.ky, first.kx), r1 = std::hypot(first.kx, first.ky);
    for (const Peak& p : peaks) {
        if (&p == &first) continue;
        double angle = std::fmod(std::abs(std::atan2(p.ky, p.kx) - a1), kTwoPi / 2);
        angle = std::min(angle, kTwoPi / 2 - angle);
        const double ratio = r1 / std::hypot(p.kx, p.ky);
        if (angle * 360 / kTwoPi >= o.min_angle_deg && ratio <= o.max_period_ratio && ratio >= 1 / o.max_period_ratio)
            return &p;
    }
    return nullptr;
}

// Edge strength ~ cos(2 pi f.p + phase) peaks where u = f.p + phase / 2 pi
// is whole: the grid lines of each direction. The cells covering the patch
// and the map from them to the image.
bool lattice_from(const Eigen::Vector2d f[2], const double phase[2], int x0, int y0, int n, Lattice& out) {
    Eigen::Matrix2d a;
    a << f[0].x(), f[0].y(), f[1].x(), f[1].y();
    if (std::abs(a.determinant()) < 1e-9) return false;
    const Eigen::Vector2d offset(phase[0] / kTwoPi, phase[1] / kTwoPi);
    Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
    for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0, 0), Eigen::Vector2d(n, 0), Eigen::Vector2d(0, n),
                                         Eigen::Vector2d(n, n)}) {
        const Eigen::Vector2d uv = a * corner + offset;
        lo = lo.cwiseMin(uv);
        hi = hi.cwiseMax(uv);
    }
    const Eigen::Vector2d first(std::floor(lo.x()), std::floor(lo.y()));
    int cols = static_cast<int>(std::ceil(hi.x()) - first.x()), rows = static_cast<int>(std::ceil(hi.y()) - first.y());
    // Cell (x, y) -> u = x + first.x, v = y + first.y -> p = a^-1 ((u, v) - offset) + patch corner.
    const Eigen::Matrix2d inv = a.inverse();
    Eigen::Matrix3d g2i = Eigen::Matrix3d::Identity();
    g2i.topLeftCorner<2, 2>() = inv;
    // Patch value (x, y) is image pixel (x0 + x, y0 + y), which covers
    // [x0 + x, x0 + x + 1): its centre lies half a pixel on.
    g2i.topRightCorner<2, 1>() = inv * (first - offset) + Eigen::Vector2d(x0 + 0.5, y0 + 0.5);
    // The field is never seen from behind: keep the grid's turn that does
    // not mirror the image.
    if (inv.determinant() < 0) {
        Eigen::Matrix3d swap;
        swap << 0, 1, 0, 1, 0, 0, 0, 0, 1;
        g2i = g2i * swap;
        std::swap(rows, cols);
    }
    out.grid_to_image = g2i;
    out.rows = rows;
    out.cols = cols;
    out.period_px[0] = 1 / f[0].norm();
    out.period_px[1] = 1 / f[1].norm();
    return true;
}

}  // namespace

std::vector<Lattice> find_lattices(const GreyView& im, const Eigen::Vector2d& aim, const LatticeOptions& o) {
    const int n = o.patch_px;
    if (!is_power_of_two(n) || im.width < n + 2 || im.height < n + 2) return {};
    const int x0 = std::clamp(static_cast<int>(std::lround(aim.x() - n / 2.0)), 1, im.width - n - 1);
    const int y0 = std::clamp(static_cast<int>(std::lround(aim.y() - n / 2.0)), 1, im.height - n - 1);
    const std::vector<double> e = edge_strength(im, x0, y0, n);
    const std::vector<Peak> peaks = spectral_peaks(e, n, o);
    std::vector<Lattice> out;
    std::vector<std::pair<const Peak*, const Peak*>> pairs;
    // The first few peaks only: past them lie the noise's.
    for (std::size_t i = 0; i < std::min<std::size_t>(peaks.size(), 8) && static_cast<int>(pairs.size()) < o.max_lattices; ++i) {
        const Peak* other = partner(peaks, peaks[i], o);
        if (!other) continue;
        const bool seen = std::any_of(pairs.begin(), pairs.end(), [&](const auto& p) {
            return (p.first == &peaks[i] && p.second == other) || (p.first == other && p.second == &peaks[i]);
        });
        if (!seen) pairs.emplace_back(&peaks[i], other);
    }
    for (const auto& [p1, p2] : pairs) {
        const Eigen::Vector2d f[2] = {refine_frequency(e, n, *p1), refine_frequency(e, n, *p2)};
        const double phase[2] = {std::arg(coefficient(e, n, f[0])), std::arg(coefficient(e, n, f[1]))};
        Lattice l;
        if (lattice_from(f, phase, x0, y0, n, l)) out.push_back(l);
    }
    return out;
}

}  // namespace umf
