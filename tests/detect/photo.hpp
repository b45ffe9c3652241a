// A simulated phone photo (640 x 480 unless asked) of a 1920 x 1080 screen showing a field
// at 30 px modules from the top-left corner, for the detector's tests.
#pragma once

#include <string>
#include <vector>

#include "shared/detect/image.hpp"
#include "shared/field/field.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"
#include "tests/support/shipped_field.hpp"

namespace umf::test {

struct Photo {
    sim::Shot shot;
    sim::FieldPlacement placement{{0, 0}, 30};
    sim::ScreenGeometry geometry;
    sim::CameraModel camera;
    sim::CameraPose pose;

    GreyView view() const {
        return {shot.grey.data, shot.grey.cols, shot.grey.rows, static_cast<std::ptrdiff_t>(shot.grey.step)};
    }
};

// A named photo setup for parameterised tests.
struct PhotoCase {
    const char* name;
    sim::ScreenKind screen;
    double opacity, pitch, yaw, roll, distance;
};

// opacity 0 shows the screen without the field.
inline Photo photograph_field(const Field& shown, double opacity, double pitch, double yaw, double roll,
                              double distance, sim::ScreenKind kind = sim::ScreenKind::blank,
                              cv::Size resolution = {640, 480}) {
    Photo p;
    cv::Mat screen = sim::make_screen(kind, {1920, 1080}, 5);
    cv::Mat mixed = opacity > 0 ? sim::mix_field(screen, shown, p.placement, opacity) : screen;
    p.camera.resolution = resolution;
    p.pose.distance_mm = distance;
    p.pose.pitch_deg = pitch;
    p.pose.yaw_deg = yaw;
    p.pose.roll_deg = roll;
    p.pose.aim_screen_px = {950, 520};
    sim::Degradation degradation;
    degradation.noise_sigma = 2;
    p.shot = sim::photograph(mixed, p.geometry, p.camera, p.pose, degradation);
    return p;
}

// A sine pulse between `lo` and `hi` over `period_s` (opacity_at's).
inline overlay::Preset sine_pulse(double lo, double hi, double period_s) {
    overlay::Preset pulse;
    pulse.opacity_min = lo;
    pulse.opacity_max = hi;
    pulse.period_s = period_s;
    return pulse;
}

// A grey cv::Mat as the detector reads it.
inline GreyView grey_view(const cv::Mat& m) { return {m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)}; }

// A phone at rest 320 mm from the screen, turned a little every way, at
// 640 x 480: the pulse scenes' camera.
inline Photo resting_phone() {
    Photo p;
    p.camera.resolution = {640, 480};
    p.pose.distance_mm = 320;
    p.pose.pitch_deg = -10;
    p.pose.yaw_deg = 14;
    p.pose.roll_deg = -20;
    p.pose.aim_screen_px = {900, 560};
    return p;
}

// `count` grey frames at 25 a second of a camera at rest (`p`'s camera,
// pose and placement) before a screen of `kind` whose field follows
// `pulse` from `start_s` on; each frame has its own noise (sigma 2).
// p.shot is the last frame.
inline std::vector<cv::Mat> film_pulse(const Field& shown, Photo& p, sim::ScreenKind kind,
                                       const overlay::Preset& pulse, int count, double start_s = 0) {
    const cv::Mat screen = sim::make_screen(kind, {1920, 1080}, 5);
    std::vector<cv::Mat> frames;
    for (int i = 0; i < count; ++i) {
        sim::Degradation degradation;
        degradation.noise_sigma = 2;
        degradation.seed = 100 + static_cast<std::uint64_t>(i);
        const double a = overlay::opacity_at(pulse, start_s + i / 25.0);
        p.shot = sim::photograph(sim::mix_field(screen, shown, p.placement, a), p.geometry, p.camera, p.pose,
                                 degradation);
        frames.push_back(p.shot.grey.clone());
    }
    return frames;
}

}  // namespace umf::test
