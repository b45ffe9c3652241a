#include "tests/sim/sensor_pipeline.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <stdexcept>

#include "tests/sim/degradation.hpp"

namespace umf::sim {
namespace {

// Noise per photosite: read noise plus shot noise growing with the signal.
void add_sensor_noise(cv::Mat& mosaic, const SensorPipeline& p) {
    if (p.read_noise <= 0 && p.shot_noise <= 0) return;
    cv::RNG rng(p.seed * 0x9E3779B97F4A7C15ull + 11);
    for (int y = 0; y < mosaic.rows; ++y) {
        auto* row = mosaic.ptr<std::uint8_t>(y);
        for (int x = 0; x < mosaic.cols; ++x) {
            const double v = row[x];
            const double sigma = std::sqrt(p.read_noise * p.read_noise + p.shot_noise * p.shot_noise * v);
            row[x] = cv::saturate_cast<std::uint8_t>(v + rng.gaussian(sigma));
        }
    }
}

cv::Mat demosaic(const cv::Mat& mosaic, Demosaic kind) {
    // OpenCV names a pattern by its second row's first two sites: RGGB
    // (R at (0, 0)) is its "BayerBG".
    cv::Mat bgr;
    switch (kind) {
    case Demosaic::bilinear: cv::demosaicing(mosaic, bgr, cv::COLOR_BayerBG2BGR); break;
    case Demosaic::edge_aware: cv::demosaicing(mosaic, bgr, cv::COLOR_BayerBG2BGR_EA); break;
    case Demosaic::vng: cv::demosaicing(mosaic, bgr, cv::COLOR_BayerBG2BGR_VNG); break;
    }
    return bgr;
}

// Shrinks by `scale`, pixel-centre aligned for every scaler: skip takes the
// photosite nearest each frame pixel's centre; bilinear interpolates its
// four nearest (no low-pass before, so it aliases as cheap scalers do); area
// averages the frame pixel's whole footprint.
cv::Mat shrink(const cv::Mat& bgr, int scale, Scaler scaler) {
    const cv::Size out(bgr.cols / scale, bgr.rows / scale);
    cv::Mat small;
    switch (scaler) {
    case Scaler::skip: cv::resize(bgr, small, out, 0, 0, cv::INTER_NEAREST_EXACT); break;
    case Scaler::bilinear: cv::resize(bgr, small, out, 0, 0, cv::INTER_LINEAR); break;
    case Scaler::area: cv::resize(bgr, small, out, 0, 0, cv::INTER_AREA); break;
    }
    return small;
}

void unsharp(cv::Mat& bgr, double amount) {
    if (amount <= 0) return;
    cv::Mat soft;
    cv::GaussianBlur(bgr, soft, cv::Size(0, 0), 1.0);
    cv::addWeighted(bgr, 1 + amount, soft, -amount, 0, bgr);
}

}  // namespace

cv::Mat bayer_mosaic(const cv::Mat& bgr8) {
    CV_Assert(bgr8.type() == CV_8UC3);
    cv::Mat mosaic(bgr8.size(), CV_8U);
    for (int y = 0; y < bgr8.rows; ++y) {
        const auto* in = bgr8.ptr<cv::Vec3b>(y);
        auto* out = mosaic.ptr<std::uint8_t>(y);
        for (int x = 0; x < bgr8.cols; ++x) {
            const bool even_row = y % 2 == 0, even_col = x % 2 == 0;
            const int channel = even_row && even_col ? 2 : !even_row && !even_col ? 0 : 1;  // BGR order
            out[x] = in[x][channel];
        }
    }
    return mosaic;
}

cv::Mat develop(const cv::Mat& sensor_bgr8, const SensorPipeline& p) {
    CV_Assert(sensor_bgr8.type() == CV_8UC3);
    if (p.scale < 1 || p.scale > 8 || sensor_bgr8.cols % p.scale || sensor_bgr8.rows % p.scale)
        throw std::invalid_argument("develop: the sensor's size must be the frame's times the scale");
    cv::Mat mosaic = bayer_mosaic(sensor_bgr8);
    add_sensor_noise(mosaic, p);
    cv::Mat frame = shrink(demosaic(mosaic, p.demosaic), p.scale, p.scaler);
    unsharp(frame, p.sharpen);
    return p.jpeg_quality > 0 ? jpeg_roundtrip(frame, p.jpeg_quality) : frame;
}

}  // namespace umf::sim
