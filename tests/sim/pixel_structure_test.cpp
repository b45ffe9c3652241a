// Tests of the screen's pixel structure: the emission keeps the average
// brightness, close up the black matrix and the stripes are resolved, and
// point sampling near the pixel pitch aliases into moire that prefiltering
// removes.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/homography.hpp"
#include "tests/sim/pixel_structure.hpp"

namespace {

using namespace umf::sim;

// Mean emission of each channel over a 2 x 2 pixel tile on a fine grid.
cv::Vec3d tile_mean(const PixelStructure& s) {
    cv::Vec3d sum(0, 0, 0);
    const int n = 600;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) sum[c] += structure_emission(s, {2.0 * (i + 0.5) / n, 2.0 * (j + 0.5) / n}, c);
    return sum / double(n * n);
}

TEST(SimPixelStructure, EmissionAveragesToOnePerChannel) {
    for (PixelLayout layout : {PixelLayout::rgb_stripe, PixelLayout::pentile})
        for (double fill : {0.5, 0.7, 1.0}) {
            const cv::Vec3d m = tile_mean({layout, fill, 3});
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 1.0, 0.03) << to_string(layout) << " fill " << fill << " c " << c;
        }
}

TEST(SimPixelStructure, CloseUpResolvesStripesAndBlackMatrix) {
    // 12 image px per screen pixel: the camera resolves every emitter.
    const cv::Mat gain = structure_gain({PixelLayout::rgb_stripe, 0.7, 3}, scaling(1.0 / 12, 1.0 / 12), {96, 96});
    std::vector<cv::Mat> ch;
    cv::split(gain, ch);
    double lo = 0, hi = 0;
    cv::minMaxLoc(ch[2], &lo, &hi);
    EXPECT_LT(lo, 0.05);  // the black matrix and the other stripes
    EXPECT_GT(hi, 3.0);   // a red emitter at 3 / 0.49
    // Red lies left of green in every pixel: red's mean column within a
    // pixel is smaller.
    const auto mean_column = [](const cv::Mat& c) {
        double sum = 0, w = 0;
        for (int y = 0; y < c.rows; ++y)
            for (int x = 0; x < c.cols; ++x) {
                sum += c.at<float>(y, x) * (x % 12);
                w += c.at<float>(y, x);
            }
        return sum / w;
    };
    EXPECT_LT(mean_column(ch[2]) + 2, mean_column(ch[1]));
}

// Spread of 16 x 16 block means of the green gain: low-frequency bands.
double band_spread(const cv::Mat& gain) {
    std::vector<cv::Mat> ch;
    cv::split(gain, ch);
    cv::Mat blocks;
    cv::resize(ch[1], blocks, {gain.cols / 16, gain.rows / 16}, 0, 0, cv::INTER_AREA);
    double lo = 0, hi = 0;
    cv::minMaxLoc(blocks, &lo, &hi);
    return hi - lo;
}

TEST(SimPixelStructure, PointSamplingNearThePitchMakesMoire) {
    // One image pixel is 1.07 screen pixels, slightly turned: the sensor's
    // grid beats against the screen's.
    const cv::Matx33d h = cv::Matx33d(std::cos(0.03), -std::sin(0.03), 0, std::sin(0.03), std::cos(0.03), 0, 0, 0, 1) *
                          scaling(1.07, 1.07);
    const cv::Mat sampled = structure_gain({PixelLayout::rgb_stripe, 0.7, 1}, h, {256, 256});
    const cv::Mat filtered = structure_gain({PixelLayout::rgb_stripe, 0.7, 12}, h, {256, 256});
    EXPECT_GT(band_spread(sampled), 0.5);
    EXPECT_LT(band_spread(filtered), 0.5 * band_spread(sampled));
}

}  // namespace
