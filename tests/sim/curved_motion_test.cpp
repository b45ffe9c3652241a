// Tests of curved motion blur: the kernel keeps the light, does not shift the
// picture, and bends away from a straight line when the path turns.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "tests/sim/curved_motion.hpp"

namespace {

using namespace umf::sim;

struct Moments {
    cv::Point2d mean;
    double minor = 0, major = 0;  // eigenvalues of the covariance
};

Moments moments(const cv::Mat& k) {
    Moments m;
    double sxx = 0, syy = 0, sxy = 0;
    for (int y = 0; y < k.rows; ++y)
        for (int x = 0; x < k.cols; ++x) m.mean += k.at<float>(y, x) * cv::Point2d(x, y);
    for (int y = 0; y < k.rows; ++y)
        for (int x = 0; x < k.cols; ++x) {
            const double w = k.at<float>(y, x), dx = x - m.mean.x, dy = y - m.mean.y;
            sxx += w * dx * dx;
            syy += w * dy * dy;
            sxy += w * dx * dy;
        }
    const double tr = sxx + syy, det = sxx * syy - sxy * sxy, disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
    m.major = tr / 2 + disc;
    m.minor = tr / 2 - disc;
    return m;
}

TEST(SimCurvedMotion, KernelKeepsLightAndCentre) {
    for (double turn : {0.0, 90.0, 200.0}) {
        const cv::Mat k = curved_motion_kernel({12, 30, turn});
        EXPECT_NEAR(cv::sum(k)[0], 1.0, 1e-5);
        const Moments m = moments(k);
        EXPECT_NEAR(m.mean.x, k.cols / 2, 0.05) << turn;
        EXPECT_NEAR(m.mean.y, k.rows / 2, 0.05) << turn;
    }
}

TEST(SimCurvedMotion, TurningPathBendsTheSmear) {
    const Moments straight = moments(curved_motion_kernel({14, 20, 0}));
    const Moments curved = moments(curved_motion_kernel({14, 20, 150}));
    EXPECT_LT(straight.minor, 0.2);          // a line: no spread across
    EXPECT_GT(curved.minor, 1.0);            // an arc: spread both ways
    EXPECT_GT(straight.major, curved.major); // the same length, folded shorter
    // A straight smear of length L has variance L^2 / 12 along it.
    EXPECT_NEAR(straight.major, 14.0 * 14.0 / 12, 1.5);
}

TEST(SimCurvedMotion, BlurSpreadsAPointAlongTheArc) {
    cv::Mat img = cv::Mat::zeros(64, 64, CV_32FC3);
    img.at<cv::Vec3f>(32, 32) = cv::Vec3f(1, 1, 1);
    apply_curved_motion(img, {10, 0, 120});
    EXPECT_NEAR(cv::sum(img)[0], 1.0, 1e-4);
    EXPECT_LT(img.at<cv::Vec3f>(32, 32)[0], 0.2f);
    EXPECT_GT(cv::countNonZero(img.reshape(1) > 0.01), 8);
}

}  // namespace
