#include "tests/sim/sequence.hpp"

#include <algorithm>
#include <cmath>

namespace umf::sim {
namespace {

constexpr double kTwoPi = 2 * CV_PI;
constexpr double kMinCycleS = 4;

// A smooth random wiggle: three sinusoids of random frequency and phase,
// scaled so that |value| <= amplitude.
class Tremor {
public:
    Tremor(cv::RNG& rng, double amplitude) {
        for (auto& w : waves_) {
            w.hz = rng.uniform(0.5, 3.0);
            w.phase = rng.uniform(0.0, kTwoPi);
            w.weight = amplitude / 3;
        }
    }
    double operator()(double t) const {
        double sum = 0;
        for (const auto& w : waves_) sum += w.weight * std::sin(kTwoPi * w.hz * t + w.phase);
        return sum;
    }

private:
    struct Wave {
        double hz = 1, phase = 0, weight = 0;
    };
    std::array<Wave, 3> waves_{};
};

// One slow cycle over the sequence: 0 at the start, 1 half way, slightly
// randomised in speed and phase per seed.
class Sweep {
public:
    Sweep(cv::RNG& rng, double duration_s) {
        period_ = std::max(duration_s, kMinCycleS) * rng.uniform(0.8, 1.0);
        phase_ = rng.uniform(-0.3, 0.3);
    }
    double rise(double t) const { return 0.5 - 0.5 * std::cos(kTwoPi * t / period_ + phase_); }  // 0..1
    double swing(double t) const { return std::sin(kTwoPi * t / period_ + phase_); }            // -1..1

private:
    double period_ = kMinCycleS;
    double phase_ = 0;
};

}  // namespace

double pulse_opacity(double t_s, double min_opacity, double max_opacity, double period_s) {
    return min_opacity + (max_opacity - min_opacity) * 0.5 * (1 - std::cos(kTwoPi * t_s / period_s));
}

const char* to_string(Motion motion) {
    switch (motion) {
    case Motion::near_far: return "near_far";
    case Motion::horizontal: return "horizontal";
    case Motion::rotation: return "rotation";
    case Motion::perspective: return "perspective";
    case Motion::general: return "general";
    }
    return "?";
}

std::vector<CameraPose> pose_trajectory(Motion motion, int frames, cv::Size screen, std::uint64_t seed,
                                        const MotionRange& range) {
    cv::RNG rng(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(motion) + 1);
    const double duration = frames / kFps;
    // Each line draws from rng in a fixed order (one statement each).
    const double px = screen.width / 1920.0;  // tremor and offsets scale with the screen
    const Tremor shake_distance(rng, 3.0);
    const Tremor shake_pitch(rng, 0.8);
    const Tremor shake_yaw(rng, 0.8);
    const Tremor shake_roll(rng, 1.0);
    const Tremor shake_x(rng, 6.0 * px);
    const Tremor shake_y(rng, 6.0 * px);
    const Sweep distance_sweep(rng, duration);
    const Sweep aim_x_sweep(rng, duration);
    const Sweep aim_y_sweep(rng, duration * 1.3);
    const Sweep roll_sweep(rng, duration);
    const Sweep tilt_sweep(rng, duration);
    const double tilt_turn_hz = rng.uniform(0.05, 0.15);  // how fast the tilt direction goes round
    const double tilt_direction = rng.uniform(0.0, kTwoPi);
    const double rest_roll = rng.uniform(-10.0, 10.0);
    const cv::Point2d rest_aim{screen.width * rng.uniform(0.4, 0.6), screen.height * rng.uniform(0.4, 0.6)};  // braces: left to right

    std::vector<CameraPose> poses;
    poses.reserve(static_cast<std::size_t>(std::max(0, frames)));
    for (int i = 0; i < frames; ++i) {
        const double t = i / kFps;
        CameraPose p;
        p.distance_mm = range.distance_mm;
        p.roll_deg = rest_roll;
        p.aim_screen_px = rest_aim;
        double tilt = 0;
        const bool all = motion == Motion::general;
        if (motion == Motion::near_far || all)
            p.distance_mm = range.near_mm + (range.far_mm - range.near_mm) * distance_sweep.rise(t);
        if (motion == Motion::horizontal || all) p.aim_screen_px.x = screen.width * (0.5 + 0.35 * aim_x_sweep.swing(t));
        if (all) p.aim_screen_px.y = screen.height * (0.5 + 0.3 * aim_y_sweep.swing(t));
        if (motion == Motion::rotation) p.roll_deg = rest_roll + 180 * roll_sweep.swing(t);
        if (all) p.roll_deg = rest_roll + 90 * roll_sweep.swing(t);
        if (motion == Motion::perspective) tilt = range.max_tilt_deg * tilt_sweep.rise(t);
        if (all) tilt = 0.75 * range.max_tilt_deg * tilt_sweep.rise(t);
        const double direction = tilt_direction + kTwoPi * tilt_turn_hz * t;
        p.pitch_deg = tilt * std::cos(direction) + shake_pitch(t);
        p.yaw_deg = tilt * std::sin(direction) + shake_yaw(t);
        p.roll_deg += shake_roll(t);
        p.distance_mm += shake_distance(t);
        p.aim_screen_px += cv::Point2d(shake_x(t), shake_y(t));
        poses.push_back(p);
    }
    return poses;
}

}  // namespace umf::sim
