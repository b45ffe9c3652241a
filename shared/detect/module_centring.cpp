#include "shared/detect/module_centring.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace umf {

namespace {

constexpr int kMaxRadius = 8;
constexpr int kMaxSteps = 16;

// One module around the point: its centre in the image, how the image point
// moves with a shift in field units, and its weight.
struct CentreSample {
    Eigen::Vector2d at, per_u, per_v;
    double weight;
};

// Sharp module edges leave the score flat while the centres stay inside
// their modules, falling off as they cross an edge. The middle of the run of
// scores above halfway between the lowest and the highest (linear between
// neighbours at either end), in profile steps from its first entry.
double plateau_middle(std::span<const double> profile) {
    const auto [lo, hi] = std::minmax_element(profile.begin(), profile.end());
    const double half = (*lo + *hi) / 2;
    const int last = static_cast<int>(profile.size()) - 1;
    const int top = static_cast<int>(hi - profile.begin());
    int left = top, right = top;
    while (left > 0 && profile[left - 1] >= half) --left;
    while (right < last && profile[right + 1] >= half) ++right;
    // Where the score crosses halfway, between the last entry above and the
    // next below; at the profile's end where it does not cross.
    auto crossing = [&](int above, int below) {
        if (below < 0 || below > last || profile[above] == profile[below]) return static_cast<double>(above);
        return above + (below - above) * (profile[above] - half) / (profile[above] - profile[below]);
    };
    return (crossing(left, left - 1) + crossing(right, right + 1)) / 2;
}

}  // namespace

Eigen::Vector2d centring_shift(const GreyView& im, const Field& f, std::span<const double> brightness,
                               const Eigen::Matrix3d& h, const Eigen::Vector2d& at, const CentringOptions& o) {
    const int radius = std::clamp(o.radius, 1, kMaxRadius);
    if (!at.allFinite() || std::abs(at.x()) > 1e6 || std::abs(at.y()) > 1e6) return Eigen::Vector2d::Zero();
    const int r0 = std::max(0, static_cast<int>(std::floor(at.y())) - radius);
    const int r1 = std::min(f.height - 1, static_cast<int>(std::floor(at.y())) + radius);
    const int c0 = std::max(0, static_cast<int>(std::floor(at.x())) - radius);
    const int c1 = std::min(f.width - 1, static_cast<int>(std::floor(at.x())) + radius);
    // The shifts tried are a module at most, so each module's image point is
    // moved along the homography's derivative at its centre: exact enough that
    // close, and a division less per sample.
    std::array<CentreSample, (2 * kMaxRadius + 1) * (2 * kMaxRadius + 1)> samples;
    std::size_t n = 0;
    double mean = 0;
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            const Eigen::Vector3d w = h * Eigen::Vector3d(c + 0.5, r + 0.5, 1.0);
            const Eigen::Vector2d p = w.hnormalized();
            const Eigen::Vector2d du = (h.block<2, 1>(0, 0) - p * h(2, 0)) / w.z();
            const Eigen::Vector2d dv = (h.block<2, 1>(0, 1) - p * h(2, 1)) / w.z();
            if (!p.allFinite() || !du.allFinite() || !dv.allFinite() || !std::isfinite(bilinear(im, p.x(), p.y())))
                continue;  // not in the image
            const std::uint8_t value = f.at(r, c);
            if (value >= brightness.size()) continue;
            samples[n++] = {p, du, dv, brightness[value]};
            mean += brightness[value];
        }
    if (n < 9) return Eigen::Vector2d::Zero();
    mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) samples[i].weight -= mean;
    auto score = [&](double su, double sv) {
        double sum = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const CentreSample& s = samples[i];
            const Eigen::Vector2d q = s.at + su * s.per_u + sv * s.per_v;
            const double v = bilinear(im, q.x(), q.y());
            if (std::isfinite(v)) sum += s.weight * v;
        }
        return sum;
    };
    // Along u at no shift in v, then along v at the shift found, then along
    // u again: off along one axis, the centres still read most of each
    // module along the other.
    Eigen::Vector2d shift = Eigen::Vector2d::Zero();
    std::array<double, 2 * kMaxSteps + 1> profile;
    const int steps = std::clamp(o.steps, 1, kMaxSteps);
    for (const int axis : {0, 1, 0}) {
        for (int k = -steps; k <= steps; ++k) {
            Eigen::Vector2d at_k = shift;
            at_k[axis] = k * o.step;
            profile[static_cast<std::size_t>(k + steps)] = score(at_k.x(), at_k.y());
        }
        shift[axis] = (plateau_middle(std::span<const double>(profile.data(), 2 * steps + 1)) - steps) * o.step;
    }
    return shift;
}

}  // namespace umf
