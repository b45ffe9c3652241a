// Tests of the phone's processing: sharpening overshoots at edges, denoising
// removes noise, local tone mapping evens out regions but keeps detail, and
// auto-exposure hunts and settles.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/phone_processing.hpp"

namespace {

using namespace umf::sim;

TEST(SimPhoneProcessing, SharpeningMakesHalosAtEdges) {
    cv::Mat step(32, 64, CV_8UC3, cv::Scalar::all(60));
    step.colRange(32, 64).setTo(cv::Scalar::all(180));
    const cv::Mat out = unsharp_mask(step, 1.0, 1.5);
    double lo = 0, hi = 0;
    cv::minMaxLoc(out.reshape(1), &lo, &hi);
    EXPECT_GT(hi, 180 + 15);  // the bright halo beside the edge
    EXPECT_LT(lo, 60 - 15);   // and the dark one
    EXPECT_EQ(out.at<cv::Vec3b>(16, 5), step.at<cv::Vec3b>(16, 5));  // flat areas untouched
}

TEST(SimPhoneProcessing, DenoiseRemovesNoise) {
    cv::Mat noisy(64, 64, CV_8UC3);
    cv::RNG rng(3);
    rng.fill(noisy, cv::RNG::NORMAL, cv::Scalar::all(128), cv::Scalar::all(6));
    PhoneProcessing p;
    p.denoise = 20;
    const cv::Mat out = process_phone_frame(noisy, p);
    cv::Scalar m0, s0, m1, s1;
    cv::meanStdDev(noisy.reshape(1), m0, s0);
    cv::meanStdDev(out.reshape(1), m1, s1);
    EXPECT_LT(s1[0], 0.6 * s0[0]);
    EXPECT_NEAR(m1[0], m0[0], 1.0);
}

TEST(SimPhoneProcessing, LocalToneMappingEvensRegionsKeepsDetail) {
    cv::Mat img(128, 256, CV_8UC3, cv::Scalar::all(40));
    img.colRange(128, 256).setTo(cv::Scalar::all(200));
    for (int y = 0; y < img.rows; y += 4) img.row(y).colRange(0, 128).setTo(cv::Scalar::all(50));  // faint lines in the dark half
    const cv::Mat out = local_tone_map(img, 0.6);
    const double dark_in = cv::mean(img(cv::Rect(20, 0, 60, 128)))[0], bright_in = cv::mean(img(cv::Rect(180, 0, 60, 128)))[0];
    const double dark_out = cv::mean(out(cv::Rect(20, 0, 60, 128)))[0], bright_out = cv::mean(out(cv::Rect(180, 0, 60, 128)))[0];
    EXPECT_LT(bright_out - dark_out, 0.8 * (bright_in - dark_in));
    const int line_in = img.at<cv::Vec3b>(64, 50)[0] - img.at<cv::Vec3b>(65, 50)[0];
    const int line_out = out.at<cv::Vec3b>(64, 50)[0] - out.at<cv::Vec3b>(65, 50)[0];
    EXPECT_GT(line_out, line_in);  // the dark region's detail is lifted with it
}

TEST(SimPhoneProcessing, ExposureHuntsThenSettles) {
    double lo = 10, hi = 0;
    for (int i = 0; i < 300; ++i) {
        const double f = exposure_hunt(i / 30.0, 5);
        lo = std::min(lo, f);
        hi = std::max(hi, f);
        EXPECT_GT(f, 0.4);
        EXPECT_LT(f, 1.6);
    }
    EXPECT_GT(hi - lo, 0.25);  // it does hunt
    // Settled most of the time: within 5 % on at least a third of frames.
    int settled = 0;
    for (int i = 0; i < 300; ++i) settled += std::abs(exposure_hunt(i / 30.0, 5) - 1) < 0.05;
    EXPECT_GT(settled, 100);
    EXPECT_EQ(exposure_hunt(1.234, 9), exposure_hunt(1.234, 9));
}

TEST(SimPhoneProcessing, MeteringDarkensABrightScreen) {
    const cv::Mat bright(100, 100, CV_32FC3, cv::Scalar::all(0.9));
    const cv::Mat dark(100, 100, CV_32FC3, cv::Scalar::all(0.05));
    EXPECT_LT(metered_exposure(bright, 0.3, 0.5, 1.6), 0.6);
    EXPECT_DOUBLE_EQ(metered_exposure(dark, 0.3, 0.5, 1.6), 1.6);
}

}  // namespace
