// Tests of the rolling shutter: no motion leaves the picture as it is, a
// turning hand makes a vertical edge lean by as much as the rows' poses say.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "tests/sim/camera.hpp"
#include "tests/sim/degradation.hpp"
#include "tests/sim/homography.hpp"
#include "tests/sim/rolling_shutter.hpp"

namespace {

using namespace umf::sim;

const ScreenGeometry kShutterScreen{{960, 540}, 344};
const CameraModel kShutterCamera{{480, 360}, 75};
const CameraPose kShutterPose{150, 0, 0, 0, {480, 270}};

// A dark screen with a bright vertical band at x = 470..490.
cv::Mat band_picture() {
    cv::Mat screen(kShutterScreen.pixels, CV_8UC3, cv::Scalar::all(20));
    screen.colRange(470, 490).setTo(cv::Scalar::all(230));
    const Shot shot = photograph(screen, kShutterScreen, kShutterCamera, kShutterPose, {});
    return to_linear(shot.bgr);
}

// The band's centre of mass along image row y.
double band_x(const cv::Mat& linear, int y) {
    double sum = 0, w = 0;
    const auto* p = linear.ptr<cv::Vec3f>(y);
    for (int x = 0; x < linear.cols; ++x) {
        const double v = p[x][1] > 0.2f ? p[x][1] : 0.0;
        sum += v * (x + 0.5);
        w += v;
    }
    return sum / w;
}

TEST(SimRollingShutter, NoMotionKeepsThePicture) {
    const cv::Mat picture = band_picture();
    const cv::Mat out = rolling_shutter(picture, kShutterScreen, kShutterCamera, kShutterPose, {}, 0.03);
    EXPECT_LT(cv::norm(out, picture, cv::NORM_INF), 1e-4);
}

TEST(SimRollingShutter, TurningHandLeansVerticalEdges) {
    const cv::Mat picture = band_picture();
    PoseVelocity v;
    v.aim_screen_px = {3000, 0};  // a quick pan to the side (the pose keeps looking at the aim point)
    const double readout = 0.03;
    const cv::Mat out = rolling_shutter(picture, kShutterScreen, kShutterCamera, kShutterPose, v, readout);
    const int top = 20, bottom = kShutterCamera.resolution.height - 21;
    // Where each row's pose puts the band's middle.
    const auto predicted = [&](int y) {
        const cv::Matx33d h = screen_to_image(kShutterScreen, kShutterCamera, pose_at(kShutterPose, v, row_time(readout, y, kShutterCamera.resolution.height)));
        const cv::Matx33d h0 = screen_to_image(kShutterScreen, kShutterCamera, kShutterPose);
        const double screen_y = apply(h0.inv(), {240, y + 0.5}).y;
        return apply(h, {480, screen_y}).x;
    };
    const double lean = band_x(out, bottom) - band_x(out, top);
    const double expected = predicted(bottom) - predicted(top);
    EXPECT_GT(std::abs(expected), 5.0);
    EXPECT_NEAR(lean, expected, 0.15 * std::abs(expected) + 0.5);
    // The centre row stays where it was.
    EXPECT_NEAR(band_x(out, kShutterCamera.resolution.height / 2), band_x(picture, kShutterCamera.resolution.height / 2), 0.3);
}

}  // namespace
