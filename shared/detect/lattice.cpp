#include "shared/detect/lattice.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

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
            const double m = std::sqrt(static_cast<double>(gx) * gx + static_cast<double>(gy) * gy);
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
    // The half plane kx in [0, n / 2) and its neighbours: columns 0 to n / 2,
    // and n - 1 for kx = -1.
    const int low = n / 2 + 1, high = 1;
    std::vector<Complex> s(e.begin(), e.end());
    fft_2d(s, n, low, high);
    std::vector<double> magnitude(s.size());
    for (int y = 0; y < n; ++y) {
        const auto at = [&](int x) {
            const std::size_t i = static_cast<std::size_t>(y) * n + static_cast<std::size_t>(x);
            magnitude[i] = std::sqrt(std::norm(s[i]));
        };
        for (int x = 0; x < low; ++x) at(x);
        for (int x = n - high; x < n; ++x) at(x);
    }
    // n is a power of two: k & (n - 1) is k modulo n, negative k too.
    const auto mag = [&](int kx, int ky) {
        return magnitude[static_cast<std::size_t>(ky & (n - 1)) * n + static_cast<std::size_t>(kx & (n - 1))];
    };
    const double r_lo = n / o.max_period_px, r_hi = n / o.min_period_px;
    std::vector<Peak> peaks;
    double band_sum = 0;
    int band_bins = 0;
    for (int ky = -n / 2 + 1; ky < n / 2; ++ky)
        for (int kx = 0; kx < n / 2; ++kx) {
            if (kx == 0 && ky <= 0) continue;
            const double r2 = static_cast<double>(kx * kx + ky * ky);
            if (r2 < r_lo * r_lo || r2 > r_hi * r_hi) continue;
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

// e^(-2 pi i freq k) for k = 0 .. n-1: one axis's phasors at a frequency.
std::vector<Complex> phasors(double freq, int n) {
    std::vector<Complex> p(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) p[static_cast<std::size_t>(k)] = std::polar(1.0, -kTwoPi * freq * k);
    return p;
}

// The phasors of the frequencies one axis's search has been at: a search
// over halving steps comes back to most of them, and each costs n sines
// and cosines.
class PhasorTable {
public:
    explicit PhasorTable(int n) : n_(n) {}
    const std::vector<Complex>& at(double freq) {
        for (const auto& [f, p] : made_)
            if (f == freq) return p;
        made_.emplace_back(freq, phasors(freq, n_));
        return made_.back().second;
    }

private:
    int n_;
    std::deque<std::pair<double, std::vector<Complex>>> made_;
};

// The patch's Fourier coefficients near a frequency, separably: the patch's
// rows transformed at one x frequency (rows[y]) and its columns at one y
// frequency (cols[x]) make the coefficient at any y frequency with the
// first, or any x frequency with the second, in n multiply-adds rather than
// n^2. Only a move of the x frequency (y frequency) makes rows (cols) anew.
// The transforms keep real and imaginary parts apart and several rows'
// sums at once, each sum in the order of its terms.
class PatchCoefficients {
public:
    PatchCoefficients(const std::vector<double>& e, int n, const Eigen::Vector2d& f)
        : e_(e), n_(n), f_(f), x_phasors_(n), y_phasors_(n) {
        transform_rows();
        transform_cols();
    }
    const Eigen::Vector2d& frequency() const { return f_; }
    Complex at() { return sum(cols_, x_phasors_.at(f_.x())); }
    // At the frequency moved by `d` along one axis (d.x() or d.y() is 0).
    Complex moved(const Eigen::Vector2d& d) {
        return d.x() != 0 ? sum(cols_, x_phasors_.at(f_.x() + d.x())) : sum(rows_, y_phasors_.at(f_.y() + d.y()));
    }
    void move(const Eigen::Vector2d& d) {
        f_ += d;
        if (d.x() != 0) transform_rows();
        if (d.y() != 0) transform_cols();
    }

private:
    // Sum of a[k] p[k], the products written out (as fft.cpp's butterflies).
    static Complex sum(const std::vector<Complex>& a, const std::vector<Complex>& p) {
        double re = 0, im = 0;
        for (std::size_t k = 0; k < a.size(); ++k) {
            re += a[k].real() * p[k].real() - a[k].imag() * p[k].imag();
            im += a[k].real() * p[k].imag() + a[k].imag() * p[k].real();
        }
        return {re, im};
    }
    static void split(const std::vector<Complex>& p, std::vector<double>& re, std::vector<double>& im) {
        re.resize(p.size());
        im.resize(p.size());
        for (std::size_t k = 0; k < p.size(); ++k) {
            re[k] = p[k].real();
            im[k] = p[k].imag();
        }
    }
    void transform_rows() {
        constexpr int kRowsAtOnce = 4;
        split(x_phasors_.at(f_.x()), re_, im_);
        rows_.assign(static_cast<std::size_t>(n_), 0);
        const std::size_t n = static_cast<std::size_t>(n_);
        for (std::size_t y = 0; y < n; y += kRowsAtOnce) {
            const std::size_t count = std::min<std::size_t>(kRowsAtOnce, n - y);
            double sum_re[kRowsAtOnce] = {}, sum_im[kRowsAtOnce] = {};
            const double* line = e_.data() + y * n;
            for (std::size_t x = 0; x < n; ++x)
                for (std::size_t j = 0; j < count; ++j) {
                    const double v = line[j * n + x];
                    sum_re[j] += v * re_[x];
                    sum_im[j] += v * im_[x];
                }
            for (std::size_t j = 0; j < count; ++j) rows_[y + j] = Complex(sum_re[j], sum_im[j]);
        }
    }
    void transform_cols() {
        const std::vector<Complex>& py = y_phasors_.at(f_.y());
        const std::size_t n = static_cast<std::size_t>(n_);
        re_.assign(n, 0);
        im_.assign(n, 0);
        for (std::size_t y = 0; y < n; ++y) {
            const double* line = e_.data() + y * n;
            const double wr = py[y].real(), wi = py[y].imag();
            for (std::size_t x = 0; x < n; ++x) {
                re_[x] += line[x] * wr;
                im_[x] += line[x] * wi;
            }
        }
        cols_.resize(n);
        for (std::size_t x = 0; x < n; ++x) cols_[x] = Complex(re_[x], im_[x]);
    }
    const std::vector<double>& e_;
    int n_;
    Eigen::Vector2d f_;
    PhasorTable x_phasors_, y_phasors_;
    std::vector<Complex> rows_, cols_;
    std::vector<double> re_, im_;  // a transform's working parts
};

// The peak's frequency to a 16th of a bin, by a search over halving steps
// (a whole bin, 1/n cycle per pixel, off would move the lines at the
// patch's edges by half a module, a 32nd of one by a 64th), and the patch's
// coefficient there.
std::pair<Eigen::Vector2d, Complex> refine_frequency(const std::vector<double>& e, int n, const Peak& p) {
    PatchCoefficients c(e, n, Eigen::Vector2d(static_cast<double>(p.kx) / n, static_cast<double>(p.ky) / n));
    Complex best = c.at();
    for (double step = 0.25 / n; step > 0.05 / n; step /= 2) {
        for (bool moved = true; moved;) {
            moved = false;
            for (const Eigen::Vector2d& d : {Eigen::Vector2d(step, 0), Eigen::Vector2d(-step, 0), Eigen::Vector2d(0, step),
                                            Eigen::Vector2d(0, -step)}) {
                const Complex m = c.moved(d);
                if (std::abs(m) > std::abs(best)) {
                    best = m;
                    c.move(d);
                    moved = true;
                }
            }
        }
    }
    return {c.frequency(), best};
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
    // A peak in several pairs is refined once.
    std::vector<std::optional<std::pair<Eigen::Vector2d, Complex>>> refined(peaks.size());
    auto refine = [&](const Peak* p) -> const std::pair<Eigen::Vector2d, Complex>& {
        auto& r = refined[static_cast<std::size_t>(p - peaks.data())];
        if (!r) r = refine_frequency(e, n, *p);
        return *r;
    };
    for (const auto& [p1, p2] : pairs) {
        const auto [f1, c1] = refine(p1);
        const auto [f2, c2] = refine(p2);
        const Eigen::Vector2d f[2] = {f1, f2};
        const double phase[2] = {std::arg(c1), std::arg(c2)};
        Lattice l;
        if (lattice_from(f, phase, x0, y0, n, l)) out.push_back(l);
    }
    return out;
}

}  // namespace umf
