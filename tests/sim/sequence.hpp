// Video-like sequences for the tracker: a pulsing field opacity and smooth
// hand-held camera paths, both at the phone's 25 frames per second.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "tests/sim/camera.hpp"

namespace umf::sim {

inline constexpr double kFps = 25;

// The provider's pulse: min at t = 0, max half a period later, a sinusoid in
// between (min + (max - min) * (1 - cos(2 pi t / period)) / 2).
double pulse_opacity(double t_s, double min_opacity, double max_opacity, double period_s);

// What a trajectory exercises: near_far sweeps the distance, horizontal the
// aim point across the screen, rotation the roll, perspective pitch and yaw
// up to max_tilt_deg, general all of them at once. Every category adds hand
// tremor (a few millimetres and a degree or so at 0.5..3 Hz).
enum class Motion { near_far, horizontal, rotation, perspective, general };

inline constexpr std::array<Motion, 5> kAllMotions = {Motion::near_far, Motion::horizontal, Motion::rotation,
                                                      Motion::perspective, Motion::general};

const char* to_string(Motion motion);

struct MotionRange {
    double distance_mm = 300;  // where the camera rests when distance is not the point
    double near_mm = 150;      // near_far sweeps from here ...
    double far_mm = 700;       // ... to here
    double max_tilt_deg = 60;  // perspective tilts this far (general three quarters of it)
};

// `frames` poses at kFps for a screen of the given pixel size. The sweeps take
// about the whole sequence (at least 4 s per cycle, so short sequences cover
// part of the range at a hand's speed). Depends only on the arguments.
std::vector<CameraPose> pose_trajectory(Motion motion, int frames, cv::Size screen_pixels, std::uint64_t seed,
                                        const MotionRange& range = {});

}  // namespace umf::sim
