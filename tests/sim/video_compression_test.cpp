// Tests of the video encoder model: faint texture in plain areas is coded
// flat, strong detail survives, gentle gradients show block steps, and the
// result is the same every time.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/degradation.hpp"
#include "tests/sim/video_compression.hpp"

namespace {

using namespace umf::sim;

// A grey frame with a faint checkerboard (8 px squares, +-amplitude).
cv::Mat faint_checker(double amplitude) {
    cv::Mat img(128, 128, CV_8UC3);
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x)
            img.at<cv::Vec3b>(y, x) = cv::Vec3b::all(cv::saturate_cast<uchar>(128 + ((x / 8 + y / 8) % 2 ? amplitude : -amplitude)));
    return img;
}

double grey_sd(const cv::Mat& bgr) {
    cv::Mat g;
    cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
    cv::Scalar m, s;
    cv::meanStdDev(g, m, s);
    return s[0];
}

TEST(SimVideoCompression, FaintTextureInPlainAreasIsCodedFlat) {
    const cv::Mat faint = faint_checker(2);
    EXPECT_GT(grey_sd(jpeg_roundtrip(faint, 95)), 1.5);  // a good still keeps it
    EXPECT_LT(grey_sd(video_compress(faint, {40, 2.5})), 0.5);
    const cv::Mat strong = faint_checker(25);
    EXPECT_GT(grey_sd(video_compress(strong, {40, 2.5})), 15);
}

TEST(SimVideoCompression, GradientsShowBlockSteps) {
    cv::Mat ramp(64, 128, CV_8UC3);
    for (int x = 0; x < ramp.cols; ++x) ramp.col(x).setTo(cv::Scalar::all(100 + x / 8.0));
    const cv::Mat out = video_compress(ramp, {0, 2.5});
    // Inside a macroblock flat, across its border a step.
    EXPECT_EQ(out.at<cv::Vec3b>(8, 17)[0], out.at<cv::Vec3b>(8, 30)[0]);
    EXPECT_GE(out.at<cv::Vec3b>(8, 32)[0] - out.at<cv::Vec3b>(8, 31)[0], 1);
}

TEST(SimVideoCompression, Deterministic) {
    cv::Mat img(96, 96, CV_8UC3);
    cv::RNG rng(4);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    const VideoCompression c{30, 2};
    EXPECT_EQ(cv::norm(video_compress(img, c), video_compress(img, c), cv::NORM_INF), 0);
}

}  // namespace
