#include "shared/detect/frame_registration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umf {

namespace {

// `image` less the mean of the box of `radius` pixels each way around each
// pixel (the box cut at the borders), plus 128, clamped to 0..255.
std::vector<std::uint8_t> less_local_mean(const GreyView& image, int radius) {
    const int w = image.width, h = image.height;
    std::vector<std::uint32_t> sums(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0);
    auto at = [&](int x, int y) -> std::uint32_t& { return sums[static_cast<std::size_t>(y) * (w + 1) + x]; };
    for (int y = 0; y < h; ++y) {
        std::uint32_t row = 0;
        for (int x = 0; x < w; ++x) {
            row += image.at(x, y);
            at(x + 1, y + 1) = at(x + 1, y) + row;
        }
    }
    std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y) {
        const int y0 = std::max(0, y - radius), y1 = std::min(h, y + radius + 1);
        for (int x = 0; x < w; ++x) {
            const int x0 = std::max(0, x - radius), x1 = std::min(w, x + radius + 1);
            const auto sum = at(x1, y1) + at(x0, y0) - at(x0, y1) - at(x1, y0);
            const float mean = static_cast<float>(sum) / static_cast<float>((x1 - x0) * (y1 - y0));
            const float v = 128.0f + static_cast<float>(image.at(x, y)) - mean;
            out[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint8_t>(std::clamp(v + 0.5f, 0.0f, 255.0f));
        }
    }
    return out;
}

}  // namespace

FramePyramid::FramePyramid(const GreyView& frame, int smallest_width) {
    Level first;
    first.width = frame.width;
    first.height = frame.height;
    first.pixels.resize(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height));
    for (int y = 0; y < frame.height; ++y)
        std::copy_n(frame.row(y), frame.width, first.pixels.data() + static_cast<std::size_t>(y) * frame.width);
    levels_.push_back(std::move(first));
    while (levels_.back().width / 2 >= smallest_width && levels_.back().height / 2 >= 8) {
        Level next;
        const GreyView half = half_size(level(levels() - 1), next.pixels);
        next.width = half.width;
        next.height = half.height;
        levels_.push_back(std::move(next));
    }
    details_.resize(levels_.size());
}

GreyView FramePyramid::detail(int i) const {
    Level& l = details_.at(static_cast<std::size_t>(i));
    if (l.pixels.empty()) {
        const GreyView grey = level(i);
        l = Level{less_local_mean(grey, kDetailRadius), grey.width, grey.height};
    }
    return {l.pixels.data(), l.width, l.height, l.width};
}

GreyView FramePyramid::level(int i) const {
    const Level& l = levels_.at(static_cast<std::size_t>(i));
    return {l.pixels.data(), l.width, l.height, l.width};
}

LevelMap::LevelMap(int level) : scale_(std::ldexp(1.0, level)) {
    const double offset = (scale_ - 1) / 2;
    to_frame_ << scale_, 0, offset, 0, scale_, offset, 0, 0, 1;
    from_frame_ << 1 / scale_, 0, -offset / scale_, 0, 1 / scale_, -offset / scale_, 0, 0, 1;
}

Eigen::Vector2d LevelMap::to_frame(const Eigen::Vector2d& level_point) const {
    return level_point * scale_ + Eigen::Vector2d::Constant((scale_ - 1) / 2);
}

Eigen::Vector2d LevelMap::from_frame(const Eigen::Vector2d& frame_point) const {
    return (frame_point - Eigen::Vector2d::Constant((scale_ - 1) / 2)) / scale_;
}

namespace {

// Pixels of a level (centres at integers) to the coordinates the alignment
// works in: the full frame's centre at 0 and its half width 1, the same at
// every level, so one homography serves them all and stays well scaled.
Eigen::Matrix3d level_to_unit(int full_width, int full_height, int level) {
    const double scale = std::ldexp(1.0, level);
    const double half = full_width / 2.0;
    Eigen::Matrix3d n = Eigen::Matrix3d::Identity();
    n(0, 0) = n(1, 1) = scale / half;
    n(0, 2) = (0.5 * scale - full_width / 2.0) / half;
    n(1, 2) = (0.5 * scale - full_height / 2.0) / half;
    return n;
}

// image.hpp's bilinear in float, for points the caller keeps inside, with
// pixel centres at whole numbers.
float bilinear_inside(const GreyView& im, double x, double y) {
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
    const std::uint8_t* a = im.row(y0) + x0;
    const std::uint8_t* b = a + im.stride;
    const float top = a[0] + fx * (a[1] - a[0]);
    const float bottom = b[0] + fx * (b[1] - b[0]);
    return top + fy * (bottom - top);
}

struct Sample {
    float u, v, grey;
    Eigen::Matrix<float, 8, 1> jacobian;
};

// The pixels of strongest gradient in `t`, with the change of their grey
// level under each of the homography's eight parameters.
std::vector<Sample> samples_of(const GreyView& t, const Eigen::Matrix3d& to_unit, int wanted) {
    std::vector<float> strength;
    strength.reserve(static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height));
    for (int y = 1; y < t.height - 1; ++y)
        for (int x = 1; x < t.width - 1; ++x) {
            float gx, gy;
            sobel(t, x, y, gx, gy);
            strength.push_back(std::abs(gx) + std::abs(gy));
        }
    if (strength.empty()) return {};
    float floor_strength = 1;
    if (static_cast<int>(strength.size()) > wanted) {
        std::vector<float> sorted = strength;
        const auto nth = sorted.end() - wanted;
        std::nth_element(sorted.begin(), nth, sorted.end());
        floor_strength = std::max(*nth, 1.0f);
    }
    // Sobel's sums are 8 times the derivative; a unit is `per_unit` pixels.
    const float per_unit = static_cast<float>(1.0 / to_unit(0, 0)) / 8;
    // Every `stride`-th of the strong pixels, spread over the whole frame
    // where many share the least strength taken.
    const auto strong = std::count_if(strength.begin(), strength.end(), [&](float s) { return s >= floor_strength; });
    const long stride = std::max<long>(1, static_cast<long>(strong) / std::max(wanted, 1));
    std::vector<Sample> out;
    out.reserve(static_cast<std::size_t>(wanted) * 2);
    std::size_t i = 0;
    long seen = 0;
    for (int y = 1; y < t.height - 1; ++y)
        for (int x = 1; x < t.width - 1; ++x, ++i) {
            if (strength[i] < floor_strength || seen++ % stride != 0) continue;
            float gx, gy;
            sobel(t, x, y, gx, gy);
            Sample s;
            s.u = static_cast<float>(to_unit(0, 0) * x + to_unit(0, 2));
            s.v = static_cast<float>(to_unit(1, 1) * y + to_unit(1, 2));
            s.grey = t.at(x, y);
            const float du = gx * per_unit, dv = gy * per_unit;
            s.jacobian << du * s.u, du * s.v, du, dv * s.u, dv * s.v, dv, -du * s.u * s.u - dv * s.u * s.v,
                -du * s.u * s.v - dv * s.v * s.v;
            out.push_back(s);
        }
    return out;
}

float median_of(std::vector<float>& values) {
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

struct Step {
    Eigen::Matrix<double, 8, 1> update = Eigen::Matrix<double, 8, 1>::Zero();
    double spread = 0;  // robust, of the grey-level differences
    double overlap = 0;
    bool solved = false;
};

// The median of grey-level differences, their robust spread about it (the
// median absolute deviation as a standard deviation) and the Huber weights'
// bound from it (at least 2 levels). Reorders `differences`.
struct RobustSpread {
    float offset = 0;
    double spread = 0;
    double huber = 2;
};

RobustSpread robust_spread(std::vector<float>& differences) {
    RobustSpread out;
    out.offset = median_of(differences);
    for (float& d : differences) d = std::abs(d - out.offset);
    out.spread = 1.4826 * median_of(differences);
    out.huber = std::max(1.345 * out.spread, 2.0);
    return out;
}

// The gain of `to`'s grey levels over `from`'s where `h` (unit coordinates)
// aligns them: weighted least squares of one on the other with an offset,
// over the flat pixels of `from` (every 4th along rows and columns), the
// weights leaving out pairs far from the offset alone (what moves apart from
// the screen). Flat pixels, not the edges the alignment samples: at an edge
// the other frame's pixel is resampled, its level pulled towards the local
// mean, and a fit through such pairs takes the gain for less. Taken once
// aligned, for the same reason. 1 where the pixels are nearly all of one
// grey, or outside [1/1.5, 1.5].
double aligned_gain(const GreyView& from, const GreyView& to, const Eigen::Matrix3d& from_to_unit,
                    const Eigen::Matrix3d& h) {
    constexpr int kStep = 4;
    constexpr float kFlat = 16;  // Sobel sums: 2 grey levels a pixel
    const Eigen::Matrix3d map = from_to_unit.inverse() * h * from_to_unit;
    std::vector<float> t, g;
    for (int y = 1; y < from.height - 1; y += kStep)
        for (int x = 1; x < from.width - 1; x += kStep) {
            float gx, gy;
            sobel(from, x, y, gx, gy);
            if (std::abs(gx) + std::abs(gy) > kFlat) continue;
            const Eigen::Vector3d q = map * Eigen::Vector3d(x, y, 1);
            if (q.z() <= 0) continue;
            const double qx = q.x() / q.z(), qy = q.y() / q.z();
            if (!(qx >= 0 && qy >= 0 && qx < to.width - 1 && qy < to.height - 1)) continue;
            t.push_back(from.at(x, y));
            g.push_back(bilinear_inside(to, qx, qy));
        }
    if (t.size() < 64) return 1;
    std::vector<float> seen(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) seen[i] = g[i] - t[i];
    const RobustSpread robust = robust_spread(seen);
    const float offset = robust.offset;
    const double huber = robust.huber;
    double sw = 0, st = 0, si = 0, stt = 0, sti = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double e = std::abs(g[i] - t[i] - offset);
        const double w = e <= huber ? 1.0 : huber / e;
        sw += w, st += w * t[i], si += w * g[i], stt += w * t[i] * t[i], sti += w * t[i] * g[i];
    }
    const double var = stt * sw - st * st;
    if (!(sw > 0) || !(var > 9 * sw * sw)) return 1;  // a spread of 3 levels at least
    const double gain = (sti * sw - st * si) / var;
    return gain >= 1 / 1.5 && gain <= 1.5 ? gain : 1;
}

// What align_step fits: a homography's eight parameters, an affine
// change's six, or nothing (the spread and overlap alone).
enum class StepFit { homography, affine, none };

// One Gauss-Newton step of the samples against `image` through `h`, with
// the samples' grey levels scaled by `gain` (the other frame's exposure).
Step align_step(const std::vector<Sample>& samples, const GreyView& image, const Eigen::Matrix3d& h,
                const Eigen::Matrix3d& unit_to_level, double gain, StepFit fit = StepFit::homography) {
    std::vector<float> diff(samples.size());
    std::vector<char> inside(samples.size(), 0);
    std::vector<float> seen;
    seen.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const Eigen::Vector3d q = unit_to_level * (h * Eigen::Vector3d(samples[i].u, samples[i].v, 1));
        if (q.z() <= 0) continue;
        const double x = q.x() / q.z(), y = q.y() / q.z();
        if (!(x >= 0 && y >= 0 && x < image.width - 1 && y < image.height - 1)) continue;
        diff[i] = bilinear_inside(image, x, y) - samples[i].grey;
        // Against the samples' grey levels at the other frame's exposure.
        if (gain != 1) diff[i] -= static_cast<float>((gain - 1) * samples[i].grey);
        inside[i] = 1;
        seen.push_back(diff[i]);
    }
    Step step;
    step.overlap = samples.empty() ? 0 : static_cast<double>(seen.size()) / static_cast<double>(samples.size());
    if (seen.size() < 16) return step;
    const RobustSpread robust = robust_spread(seen);
    const float offset = robust.offset;
    const double huber = robust.huber;
    step.spread = robust.spread;
    if (fit == StepFit::none) return step;
    Eigen::Matrix<double, 8, 8> normal = Eigen::Matrix<double, 8, 8>::Zero();
    Eigen::Matrix<double, 8, 1> rhs = Eigen::Matrix<double, 8, 1>::Zero();
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (!inside[i]) continue;
        const double e = diff[i] - offset;
        const double w = std::abs(e) <= huber ? 1.0 : huber / std::abs(e);
        // The template is `gain` times the samples': so are its gradients.
        const Eigen::Matrix<double, 8, 1> j = gain * samples[i].jacobian.cast<double>();
        normal.selfadjointView<Eigen::Lower>().rankUpdate(j, w);
        rhs += w * e * j;
    }
    normal = normal.selfadjointView<Eigen::Lower>();
    if (fit == StepFit::affine) {
        const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(normal.topLeftCorner<6, 6>());
        if (solver.info() != Eigen::Success) return step;
        step.update.head<6>() = solver.solve(rhs.head<6>());
    } else {
        const Eigen::LDLT<Eigen::Matrix<double, 8, 8>> solver(normal);
        if (solver.info() != Eigen::Success) return step;
        step.update = solver.solve(rhs);
    }
    step.solved = step.update.allFinite();
    return step;
}

Eigen::Matrix3d as_matrix(const Eigen::Matrix<double, 8, 1>& p) {
    Eigen::Matrix3d m;
    m << 1 + p(0), p(1), p(2), p(3), 1 + p(4), p(5), p(6), p(7), 1;
    return m;
}

// How far (pixels of the level) a corner of the frame moves under `m`.
double corner_motion(const Eigen::Matrix3d& m, const Eigen::Matrix3d& unit_to_level, double aspect) {
    double most = 0;
    for (double u : {-1.0, 1.0})
        for (double v : {-aspect, aspect}) {
            const Eigen::Vector3d a = unit_to_level * Eigen::Vector3d(u, v, 1);
            const Eigen::Vector3d b = unit_to_level * (m * Eigen::Vector3d(u, v, 1));
            if (b.z() <= 0) return 1e9;
            most = std::max(most, (b.head<2>() / b.z() - a.head<2>() / a.z()).norm());
        }
    return most;
}

}  // namespace

FrameRegistration register_frames(const FramePyramid& from, const FramePyramid& to, const Eigen::Matrix3d& guess,
                                  const RegistrationOptions& options) {
    if (from.width() != to.width() || from.height() != to.height() || from.levels() == 0)
        throw std::invalid_argument("register_frames: the frames differ in size");
    const int w = from.width(), h = from.height();
    const Eigen::Matrix3d full_to_unit = level_to_unit(w, h, 0);
    const Eigen::Matrix3d guess_warp = full_to_unit * guess * full_to_unit.inverse();
    Eigen::Matrix3d warp = guess_warp;
    const int coarsest = std::min(from.levels(), to.levels()) - 1;
    const int finest = std::clamp(options.finest_level, 0, coarsest);
    const double aspect = static_cast<double>(h) / w;
    FrameRegistration result;
    Step last;
    std::vector<Sample> samples;  // at the end, the finest level's
    // The gain is of grey levels, not of their difference from a local mean.
    const bool detail = options.detail && !options.fit_gain;
    auto image = [&](const FramePyramid& p, int level) { return detail ? p.detail(level) : p.level(level); };
    auto align = [&](int level, double gain) {
        const Eigen::Matrix3d unit_to_level = level_to_unit(w, h, level).inverse();
        const StepFit fit = options.affine_coarse && level == coarsest && coarsest > finest ? StepFit::affine
                                                                                            : StepFit::homography;
        for (int it = 0; it < options.iterations; ++it) {
            last = align_step(samples, image(to, level), warp, unit_to_level, gain, fit);
            if (!last.solved) break;
            const Eigen::Matrix3d inverse_step = as_matrix(last.update).inverse();
            warp = warp * inverse_step;
            warp /= warp(2, 2);
            if (corner_motion(inverse_step, unit_to_level, aspect) < options.converged_px) break;
        }
    };
    for (int level = coarsest; level >= finest; --level) {
        samples = samples_of(image(from, level), level_to_unit(w, h, level), options.samples);
        align(level, 1);
    }
    const Eigen::Matrix3d finest_to_unit = level_to_unit(w, h, finest);
    // The exposure's gain, from the frames as aligned with an offset alone,
    // and the finest level aligned again with it where it is more than a
    // small change (the Huber weights carry the alignment through that).
    double gain = 1;
    if (options.fit_gain) {
        gain = aligned_gain(from.level(finest), to.level(finest), finest_to_unit, warp);
        if (std::abs(gain - 1) > options.least_gain)
            align(finest, gain);
        else
            gain = 1;
    }
    // The spread and overlap where the alignment ended, against the spread
    // of the frames as they lie (the screen not moved): sharp content leaves
    // a spread of many levels even where aligned exactly (the pixels sample
    // its edges at other phases), so the alignment is judged by how much it
    // explains as well as by what it leaves.
    last = align_step(samples, image(to, finest), warp, finest_to_unit.inverse(), gain);
    auto spread_at = [&](const Eigen::Matrix3d& h) {
        return align_step(samples, image(to, finest), h, finest_to_unit.inverse(), gain, StepFit::none).spread;
    };
    result.homography = full_to_unit.inverse() * warp * full_to_unit;
    result.homography /= result.homography(2, 2);
    result.residual = last.spread;
    result.unmoved_residual = spread_at(Eigen::Matrix3d::Identity());
    result.guess_residual = guess.isIdentity() ? result.unmoved_residual : spread_at(guess_warp);
    result.overlap = last.overlap;
    result.gain = gain;
    result.on_detail = detail;
    const bool explained =
        last.spread <= options.max_residual || last.spread <= options.max_share * result.unmoved_residual;
    result.registered = last.solved && result.homography.allFinite() && explained && last.overlap >= options.min_overlap;
    return result;
}

GreyView warp_frame(const GreyView& frame, const Eigen::Matrix3d& homography, const GreyView& outside,
                    std::vector<std::uint8_t>& out) {
    if (outside.width != frame.width || outside.height != frame.height)
        throw std::invalid_argument("warp_frame: the frames differ in size");
    const int w = frame.width, h = frame.height;
    out.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    const Eigen::Matrix3d back = homography.inverse();
    for (int y = 0; y < h; ++y) {
        std::uint8_t* dst = out.data() + static_cast<std::size_t>(y) * w;
        const std::uint8_t* keep = outside.row(y);
        Eigen::Vector3d q = back * Eigen::Vector3d(0, y, 1);
        const Eigen::Vector3d dq = back.col(0);
        for (int x = 0; x < w; ++x, q += dq) {
            if (q.z() <= 0) {
                dst[x] = keep[x];
                continue;
            }
            const double sx = q.x() / q.z(), sy = q.y() / q.z();
            if (sx >= 0 && sy >= 0 && sx < w - 1 && sy < h - 1)
                dst[x] = static_cast<std::uint8_t>(bilinear_inside(frame, sx, sy) + 0.5f);
            else
                dst[x] = keep[x];
        }
    }
    return {out.data(), w, h, w};
}

}  // namespace umf
