// The third camera model's development: where it keeps the picture, and
// that its cheap scalers alias what the area average does not.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "tests/sim/sensor_pipeline.hpp"

namespace umf::sim {
namespace {

SensorPipeline clean(Scaler scaler, int scale = 3) {
    SensorPipeline p;
    p.scale = scale;
    p.scaler = scaler;
    p.read_noise = p.shot_noise = p.sharpen = 0;
    p.jpeg_quality = 0;
    return p;
}

TEST(SensorPipeline, TheMosaicKeepsOneColourPerPhotositeRggb) {
    cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(10, 20, 30));  // B 10, G 20, R 30
    const cv::Mat m = bayer_mosaic(bgr);
    EXPECT_EQ(m.at<std::uint8_t>(0, 0), 30);
    EXPECT_EQ(m.at<std::uint8_t>(0, 1), 20);
    EXPECT_EQ(m.at<std::uint8_t>(1, 0), 20);
    EXPECT_EQ(m.at<std::uint8_t>(1, 1), 10);
}

TEST(SensorPipeline, AFlatGreyStaysFlatWithEveryDemosaicAndScaler) {
    const cv::Mat sensor(96, 120, CV_8UC3, cv::Scalar(140, 140, 140));
    for (Demosaic d : {Demosaic::bilinear, Demosaic::edge_aware, Demosaic::vng})
        for (Scaler s : {Scaler::skip, Scaler::bilinear, Scaler::area}) {
            SensorPipeline p = clean(s);
            p.demosaic = d;
            const cv::Mat frame = develop(sensor, p);
            ASSERT_EQ(frame.size(), cv::Size(40, 32));
            double lo = 0, hi = 0;
            cv::minMaxLoc(frame.reshape(1), &lo, &hi);
            EXPECT_GE(lo, 138) << static_cast<int>(d) << " " << static_cast<int>(s);
            EXPECT_LE(hi, 142) << static_cast<int>(d) << " " << static_cast<int>(s);
        }
}

// A grey step at sensor column 90 (frame column 30 at scale 3) stays at
// frame column 30 for every scaler: the frame's truth is the sensor's / 3.
TEST(SensorPipeline, AnEdgeLandsWhereTheSensorsTruthSaysDividedByTheScale) {
    cv::Mat sensor(60, 180, CV_8UC3, cv::Scalar(40, 40, 40));
    sensor.colRange(90, 180).setTo(cv::Scalar(200, 200, 200));
    for (Scaler s : {Scaler::skip, Scaler::bilinear, Scaler::area}) {
        cv::Mat grey;
        cv::cvtColor(develop(sensor, clean(s)), grey, cv::COLOR_BGR2GRAY);
        // The edge's place: where the row crosses half way, interpolated.
        const auto* row = grey.ptr<std::uint8_t>(10);
        double at = -1;
        for (int x = 1; x < grey.cols; ++x)
            if (row[x - 1] < 120 && row[x] >= 120) at = x - 1 + (120.0 - row[x - 1]) / (row[x] - row[x - 1]) + 0.5;
        EXPECT_NEAR(at, 30.0, 0.6) << static_cast<int>(s);
    }
}

// A screen's pixel structure near the photosite pitch: stripes of 2.2
// photosites. The area average (three photosites wide) keeps a fifth of
// their swing; skipping photosites keeps twice that and more, folded into a
// coarse beat.
TEST(SensorPipeline, SkippingPhotositesFoldsFineStripesIntoMoireTheAreaAverageDoesNot) {
    cv::Mat sensor(90, 360, CV_8UC3);
    for (int x = 0; x < sensor.cols; ++x) {
        const double v = 128 + 100 * std::sin(2 * CV_PI * x / 2.2);
        sensor.col(x).setTo(cv::Scalar::all(v));
    }
    auto spread = [&](Scaler s) {
        cv::Mat grey;
        cv::cvtColor(develop(sensor, clean(s)), grey, cv::COLOR_BGR2GRAY);
        cv::Scalar mean, stddev;
        cv::meanStdDev(grey.rowRange(10, 20).colRange(4, grey.cols - 4), mean, stddev);
        return stddev[0];
    };
    const double area = spread(Scaler::area), skip = spread(Scaler::skip);
    EXPECT_LT(area, 20.0);
    EXPECT_GT(skip, 1.8 * area);
}

TEST(SensorPipeline, ASensorThatIsNotAWholeMultipleIsRefused) {
    EXPECT_THROW(develop(cv::Mat(100, 100, CV_8UC3, cv::Scalar::all(0)), clean(Scaler::area, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace umf::sim
