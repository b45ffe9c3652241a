// A phone's rolling shutter under hand motion: the sensor reads its rows one
// after the other, so each row sees the screen from the camera's pose at its
// own moment. Straight edges lean and bend, and the picture stretches or
// shears while the hand moves.
//
// Rendered by resampling a picture taken at the centre row's pose: image
// point (x, y) of row y takes the light the centre-row picture shows at the
// same screen point, H_centre(H_row(y)^-1 (x, y)). The image centre's row is
// exposed at the centre moment, so the ground truth at the image centre is
// that of the centre pose.
#pragma once

#include <opencv2/core.hpp>

#include "tests/sim/camera.hpp"

namespace umf::sim {

// How fast the hand moves the camera, per second.
struct PoseVelocity {
    double distance_mm = 0;
    double pitch_deg = 0;
    double yaw_deg = 0;
    double roll_deg = 0;
    cv::Point2d aim_screen_px;
};

// The pose t seconds after `pose` at constant velocity.
CameraPose pose_at(const CameraPose& pose, const PoseVelocity& velocity, double t_s);

// Seconds from the centre row's exposure to row y's (continuous row
// coordinate y + 0.5 for row y): readout_s * ((y + 0.5) / rows - 0.5).
double row_time(double readout_s, int y, int rows);

// `centre_picture` (CV_32FC3, the camera's resolution, taken at `pose`)
// as the rolling shutter reads it while the camera moves at `velocity`,
// the whole frame taking readout_s from the first row to the last. Points
// outside the centre picture repeat its border.
cv::Mat rolling_shutter(const cv::Mat& centre_picture, const ScreenGeometry& screen, const CameraModel& camera,
                        const CameraPose& pose, const PoseVelocity& velocity, double readout_s);

}  // namespace umf::sim
