#include "tests/sim/degradation.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <stdexcept>

namespace umf::sim {
namespace {

constexpr double kDisplayGamma = 2.2;

// Independent streams for the different random effects of one seed.
cv::RNG stream(std::uint64_t seed, std::uint64_t which) {
    return cv::RNG(seed * 0x9E3779B97F4A7C15ull + which * 0xD1B54A32D192ED03ull + 1);
}

float linear_value(int value) { return static_cast<float>(std::pow(value / 255.0, kDisplayGamma)); }

}  // namespace

cv::Mat to_linear(const cv::Mat& bgr8) {
    CV_Assert(bgr8.type() == CV_8UC3);
    cv::Mat lut(1, 256, CV_32F);
    for (int i = 0; i < 256; ++i) lut.at<float>(i) = linear_value(i);
    cv::Mat out;
    cv::LUT(bgr8, lut, out);
    return out;
}

cv::Vec3f to_linear(const cv::Vec3b& bgr) { return {linear_value(bgr[0]), linear_value(bgr[1]), linear_value(bgr[2])}; }

cv::Mat to_output(const cv::Mat& linear, double gamma, double noise_sigma, std::uint64_t seed) {
    CV_Assert(linear.type() == CV_32FC3 && gamma > 0);
    cv::Mat v;
    cv::max(linear, 0.0, v);
    cv::min(v, 1.0, v);
    cv::pow(v, gamma / kDisplayGamma, v);
    v *= 255.0;
    if (noise_sigma > 0) {
        cv::Mat noise(v.size(), v.type());
        cv::RNG rng = stream(seed, 1);
        rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(noise_sigma));
        v += noise;
    }
    cv::Mat out;
    v.convertTo(out, CV_8UC3);  // rounds and saturates
    return out;
}

cv::Mat subpixel_stripes(const cv::Mat& linear) {
    CV_Assert(linear.type() == CV_32FC3);
    cv::Mat out(linear.rows, linear.cols * 3, CV_32FC3, cv::Scalar::all(0));
    for (int y = 0; y < linear.rows; ++y) {
        const auto* in = linear.ptr<cv::Vec3f>(y);
        auto* o = out.ptr<cv::Vec3f>(y);
        for (int x = 0; x < linear.cols; ++x) {
            o[3 * x + 0][2] = 3 * in[x][2];  // red stripe on the left (BGR order: channel 2)
            o[3 * x + 1][1] = 3 * in[x][1];
            o[3 * x + 2][0] = 3 * in[x][0];
        }
    }
    return out;
}

cv::Mat pixel_grid(const cv::Mat& linear) {
    CV_Assert(linear.type() == CV_32FC3);
    cv::Mat out(linear.rows * 3, linear.cols * 3, CV_32FC3, cv::Scalar::all(0));
    for (int y = 0; y < linear.rows; ++y) {
        const auto* in = linear.ptr<cv::Vec3f>(y);
        for (int row = 0; row < 2; ++row) {
            auto* o = out.ptr<cv::Vec3f>(3 * y + row);
            for (int x = 0; x < linear.cols; ++x) {
                o[3 * x + 0][2] = 4.5f * in[x][2];  // red on the left (BGR order: channel 2)
                o[3 * x + 1][1] = 4.5f * in[x][1];
                o[3 * x + 2][0] = 4.5f * in[x][0];
            }
        }
    }
    return out;
}

cv::Mat motion_kernel(double length_px, double angle_deg) {
    const double a = angle_deg * CV_PI / 180;
    const cv::Point2d dir(std::cos(a), std::sin(a));
    const int half = static_cast<int>(std::ceil(length_px / 2)) + 1;
    cv::Mat k = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
    // Splat many points along the segment bilinearly: a smooth kernel whose
    // length varies continuously with length_px.
    const int samples = std::max(2, static_cast<int>(std::ceil(length_px * 8)));
    for (int i = 0; i < samples; ++i) {
        const double t = (i + 0.5) / samples - 0.5;
        const cv::Point2d p = cv::Point2d(half, half) + t * length_px * dir;
        const int x = static_cast<int>(std::floor(p.x));
        const int y = static_cast<int>(std::floor(p.y));
        const double fx = p.x - x;
        const double fy = p.y - y;
        k.at<float>(y, x) += static_cast<float>((1 - fx) * (1 - fy));
        k.at<float>(y, x + 1) += static_cast<float>(fx * (1 - fy));
        k.at<float>(y + 1, x) += static_cast<float>((1 - fx) * fy);
        k.at<float>(y + 1, x + 1) += static_cast<float>(fx * fy);
    }
    return k / cv::sum(k)[0];
}

void apply_optics(cv::Mat& linear, const Degradation& d) {
    if (d.defocus_sigma_px > 0) cv::GaussianBlur(linear, linear, {0, 0}, d.defocus_sigma_px, 0, cv::BORDER_REFLECT);
    if (d.motion_blur_px > 0)
        cv::filter2D(linear, linear, -1, motion_kernel(d.motion_blur_px, d.motion_angle_deg), {-1, -1}, 0,
                     cv::BORDER_REFLECT);
}

void apply_glare(cv::Mat& linear, double strength, std::uint64_t seed) {
    if (strength <= 0) return;
    cv::RNG rng = stream(seed, 2);
    const double cx = rng.uniform(0.15, 0.85) * linear.cols;
    const double cy = rng.uniform(0.15, 0.85) * linear.rows;
    const double sigma = rng.uniform(0.12, 0.3) * linear.cols;
    // A lamp's reflection is white light added to whatever the screen shows.
    // The Gaussian separates into a column and a row factor.
    const auto profile = [sigma](int n, double centre) {
        std::vector<float> g(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) g[i] = static_cast<float>(std::exp(-(i + 0.5 - centre) * (i + 0.5 - centre) / (2 * sigma * sigma)));
        return g;
    };
    const std::vector<float> gx = profile(linear.cols, cx);
    const std::vector<float> gy = profile(linear.rows, cy);
    for (int y = 0; y < linear.rows; ++y) {
        auto* p = linear.ptr<cv::Vec3f>(y);
        const auto row = static_cast<float>(strength) * gy[y];
        for (int x = 0; x < linear.cols; ++x) p[x] += cv::Vec3f::all(row * gx[x]);
    }
}

cv::Mat jpeg_roundtrip(const cv::Mat& bgr8, int quality) {
    std::vector<uchar> bytes;
    if (!cv::imencode(".jpg", bgr8, bytes, {cv::IMWRITE_JPEG_QUALITY, quality}))
        throw std::runtime_error("JPEG encoding failed");
    cv::Mat out = cv::imdecode(bytes, cv::IMREAD_COLOR);
    if (out.empty()) throw std::runtime_error("JPEG decoding failed");
    return out;
}

}  // namespace umf::sim
