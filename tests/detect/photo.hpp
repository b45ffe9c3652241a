// A simulated 640 x 480 phone photo of a 1920 x 1080 screen showing a field
// at 30 px modules from the top-left corner, for the detector's tests.
#pragma once

#include <string>

#include "shared/detect/image.hpp"
#include "shared/field/field.hpp"
#include "shared/field/field_io.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"

namespace umf::test {

inline Field shipped_field(const char* name) { return load_field(std::string(UMF_DATA_DIR) + "/fields/" + name); }

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
                              double distance, sim::ScreenKind kind = sim::ScreenKind::blank) {
    Photo p;
    cv::Mat screen = sim::make_screen(kind, {1920, 1080}, 5);
    cv::Mat mixed = opacity > 0 ? sim::mix_field(screen, shown, p.placement, opacity) : screen;
    p.camera.resolution = {640, 480};
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

}  // namespace umf::test
