// Tests of the simulated camera's image degradations: deterministic per seed
// and pushing the image the physically expected way.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/camera.hpp"
#include "tests/sim/degradation.hpp"
#include "tests/sim/screen_content.hpp"

namespace {

using namespace umf::sim;

// A quarter-size setup: the effects do not need full resolution.
const ScreenGeometry kDegradedScreen{{960, 540}, 527};
const CameraModel kDegradedCamera{{640, 360}, 65};
const CameraPose kDegradedPose{350, 10, -5, 3, {480, 270}};

Shot shoot(const Degradation& d, ScreenKind kind = ScreenKind::web_page) {
    return photograph(make_screen(kind, kDegradedScreen.pixels, 7), kDegradedScreen, kDegradedCamera, kDegradedPose, d);
}

double gradient_energy(const cv::Mat& grey) {
    cv::Mat gx, gy;
    cv::Sobel(grey, gx, CV_32F, 1, 0);
    cv::Sobel(grey, gy, CV_32F, 0, 1);
    return cv::sum(gx.mul(gx) + gy.mul(gy))[0];
}

double mean_grey(const Shot& shot) { return cv::mean(shot.grey)[0]; }

TEST(SimDegradation, DeterministicPerSeed) {
    Degradation d;
    d.noise_sigma = 4;
    d.glare = 0.4;
    d.motion_blur_px = 3.5;
    d.jpeg_quality = 80;
    d.seed = 11;
    const Shot a = shoot(d);
    const Shot b = shoot(d);
    EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0);
    d.seed = 12;
    const Shot c = shoot(d);
    EXPECT_GT(cv::norm(a.bgr, c.bgr, cv::NORM_L1), 0);
}

TEST(SimDegradation, NoDegradationKeepsScreenValues) {
    const Shot shot = shoot({}, ScreenKind::blank);
    EXPECT_EQ(shot.bgr.at<cv::Vec3b>(180, 320), cv::Vec3b(128, 128, 128));
    EXPECT_EQ(shot.grey.at<uchar>(180, 320), 128);
}

TEST(SimDegradation, JpegDecodesAndStaysClose) {
    Degradation d;
    d.jpeg_quality = 70;
    const Shot jpeg = shoot(d);
    const Shot raw = shoot({});
    ASSERT_EQ(jpeg.bgr.size(), kDegradedCamera.resolution);
    ASSERT_EQ(jpeg.bgr.type(), CV_8UC3);
    EXPECT_GT(cv::norm(jpeg.bgr, raw.bgr, cv::NORM_L1), 0);
    EXPECT_LT(cv::norm(jpeg.bgr, raw.bgr, cv::NORM_L1) / double(raw.bgr.total() * 3), 6);
}

TEST(SimDegradation, GlareAndExposureChangeBrightness) {
    Degradation glare;
    glare.glare = 0.6;
    Degradation dark;
    dark.exposure = 0.5;
    const double plain = mean_grey(shoot({}));
    EXPECT_GT(mean_grey(shoot(glare)), plain + 10);
    EXPECT_LT(mean_grey(shoot(dark)), plain - 10);
}

TEST(SimDegradation, BlurLowersGradientEnergy) {
    Degradation defocus;
    defocus.defocus_sigma_px = 2;
    Degradation motion;
    motion.motion_blur_px = 8;
    motion.motion_angle_deg = 30;
    const double sharp = gradient_energy(shoot({}).grey);
    EXPECT_LT(gradient_energy(shoot(defocus).grey), 0.5 * sharp);
    EXPECT_LT(gradient_energy(shoot(motion).grey), 0.5 * sharp);
}

TEST(SimDegradation, SubpixelStripesKeepTheAverage) {
    // Close enough that one screen pixel spans several image pixels: the
    // stripes show as colour, the average stays the screen's grey. (Stripes
    // are three times as bright as their pixel, so a grey above about 155
    // would clip in a resolved stripe and lose average.)
    const cv::Mat grey_screen(kDegradedScreen.pixels, CV_8UC3, cv::Scalar::all(120));
    Degradation d;
    d.subpixels = true;
    const CameraPose close{60, 0, 0, 0, {480, 270}};
    const Shot shot = photograph(grey_screen, kDegradedScreen, kDegradedCamera, close, d);
    const cv::Mat centre = shot.bgr(cv::Rect(200, 100, 240, 160));
    cv::Scalar mean, stddev;
    cv::meanStdDev(centre, mean, stddev);
    const cv::Mat centre_linear = to_linear(centre);
    const double expected = std::pow(120 / 255.0, 2.2);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(cv::mean(centre_linear)[c], expected, 0.03 * expected) << "channel " << c;
        EXPECT_GT(stddev[c], 20) << "channel " << c;
    }
}

TEST(SimDegradation, PixelGridKeepsTheAverageAndShowsTheBlackMatrix) {
    // Each pixel is R, G, B over two rows and a black row: resolved up
    // close, every image row through the black matrix is dark in every
    // channel while the rows of stripes are bright; the average stays the
    // screen's grey. (Stripes are 4.5 times as bright as their pixel: a grey
    // of 90 keeps them below clipping.)
    const cv::Mat grey_screen(kDegradedScreen.pixels, CV_8UC3, cv::Scalar::all(90));
    const cv::Mat linear = to_linear(grey_screen(cv::Rect(0, 0, 8, 8)));
    const cv::Mat grid = pixel_grid(linear);
    ASSERT_EQ(grid.size(), cv::Size(24, 24));
    const double expected = std::pow(90 / 255.0, 2.2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(cv::mean(grid)[c], expected, 1e-4 * expected) << "channel " << c;
    EXPECT_EQ(cv::norm(grid.row(2)), 0.0);   // the black matrix under the first pixel row
    EXPECT_GT(cv::norm(grid.row(1)), 0.0);

    Degradation d;
    d.pixel_grid = true;
    const CameraPose close{60, 0, 0, 0, {480, 270}};
    const Shot shot = photograph(grey_screen, kDegradedScreen, kDegradedCamera, close, d);
    const cv::Mat centre_linear = to_linear(shot.bgr(cv::Rect(200, 100, 240, 160)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(cv::mean(centre_linear)[c], expected, 0.05 * expected) << "channel " << c;
    // Across the rows: the black matrix makes the brightness swing.
    cv::Mat grey;
    cv::cvtColor(shot.bgr(cv::Rect(200, 100, 240, 160)), grey, cv::COLOR_BGR2GRAY);
    cv::Mat row_means;
    cv::reduce(grey, row_means, 1, cv::REDUCE_AVG, CV_64F);
    double lo, hi;
    cv::minMaxLoc(row_means, &lo, &hi);
    EXPECT_GT(hi - lo, 30);
}

TEST(SimDegradation, MotionKernelIsNormalisedAndOriented) {
    const cv::Mat k = motion_kernel(6.5, 90);
    EXPECT_NEAR(cv::sum(k)[0], 1.0, 1e-5);
    const int c = k.cols / 2;
    EXPECT_GT(k.at<float>(c + 2, c), 0);  // along y
    EXPECT_EQ(k.at<float>(c, c + 2), 0);  // not along x
}

}  // namespace
