#include "tests/sim/rolling_shutter.hpp"

#include <opencv2/imgproc.hpp>

namespace umf::sim {

CameraPose pose_at(const CameraPose& p, const PoseVelocity& v, double t) {
    CameraPose q = p;
    q.distance_mm += v.distance_mm * t;
    q.pitch_deg += v.pitch_deg * t;
    q.yaw_deg += v.yaw_deg * t;
    q.roll_deg += v.roll_deg * t;
    q.aim_screen_px += v.aim_screen_px * t;
    return q;
}

double row_time(double readout_s, int y, int rows) { return readout_s * ((y + 0.5) / rows - 0.5); }

cv::Mat rolling_shutter(const cv::Mat& picture, const ScreenGeometry& screen, const CameraModel& camera,
                        const CameraPose& pose, const PoseVelocity& velocity, double readout_s) {
    CV_Assert(picture.type() == CV_32FC3 && picture.size() == camera.resolution);
    if (readout_s == 0) return picture.clone();
    const cv::Matx33d centre = screen_to_image(screen, camera, pose);
    cv::Mat map_x(picture.size(), CV_32F), map_y(picture.size(), CV_32F);
    for (int y = 0; y < picture.rows; ++y) {
        const cv::Matx33d row_inv = screen_to_image(screen, camera, pose_at(pose, velocity, row_time(readout_s, y, picture.rows))).inv();
        const cv::Matx33d m = centre * row_inv;
        auto* mx = map_x.ptr<float>(y);
        auto* my = map_y.ptr<float>(y);
        for (int x = 0; x < picture.cols; ++x) {
            const cv::Vec3d q = m * cv::Vec3d(x + 0.5, y + 0.5, 1.0);
            // remap's coordinates are pixel indices: centre of pixel (x, y) at (x, y).
            mx[x] = static_cast<float>(q[0] / q[2] - 0.5);
            my[x] = static_cast<float>(q[1] / q[2] - 0.5);
        }
    }
    cv::Mat out;
    cv::remap(picture, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    return out;
}

}  // namespace umf::sim
