#include "tests/sim/phone_processing.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace umf::sim {

cv::Mat unsharp_mask(const cv::Mat& bgr8, double amount, double sigma_px) {
    CV_Assert(bgr8.type() == CV_8UC3);
    if (amount <= 0) return bgr8.clone();
    cv::Mat f, blurred;
    bgr8.convertTo(f, CV_32FC3);
    cv::GaussianBlur(f, blurred, {0, 0}, sigma_px, 0, cv::BORDER_REFLECT);
    cv::Mat sharp = f + amount * (f - blurred);
    cv::Mat out;
    sharp.convertTo(out, CV_8UC3);
    return out;
}

cv::Mat local_tone_map(const cv::Mat& bgr8, double strength) {
    CV_Assert(bgr8.type() == CV_8UC3);
    if (strength <= 0) return bgr8.clone();
    cv::Mat f, grey, local;
    bgr8.convertTo(f, CV_32FC3, 1.0 / 255);
    cv::cvtColor(f, grey, cv::COLOR_BGR2GRAY);
    const double sigma = std::max(2.0, bgr8.cols / 16.0);
    cv::GaussianBlur(grey, local, {0, 0}, sigma, 0, cv::BORDER_REFLECT);
    const double global = std::max(0.02, cv::mean(grey)[0]);
    cv::Mat gain;
    cv::max(local, 0.02, local);
    cv::divide(global, local, gain);
    cv::pow(gain, strength, gain);
    cv::min(gain, 4.0, gain);
    cv::Mat gain3;
    cv::merge(std::vector<cv::Mat>{gain, gain, gain}, gain3);
    cv::Mat out;
    cv::Mat(f.mul(gain3)).convertTo(out, CV_8UC3, 255);
    return out;
}

cv::Mat process_phone_frame(const cv::Mat& bgr8, const PhoneProcessing& p) {
    CV_Assert(bgr8.type() == CV_8UC3);
    cv::Mat v = bgr8;
    if (p.denoise > 0) {
        cv::Mat d;
        cv::bilateralFilter(v, d, 5, p.denoise, 2.0, cv::BORDER_REFLECT);
        v = d;
    }
    if (p.local_tone > 0) v = local_tone_map(v, p.local_tone);
    if (p.sharpen_amount > 0) v = unsharp_mask(v, p.sharpen_amount, p.sharpen_sigma_px);
    return v.data == bgr8.data ? bgr8.clone() : v;
}

double exposure_hunt(double t_s, std::uint64_t seed) {
    cv::RNG rng(seed * 0x9E3779B97F4A7C15ull + 0x5151);
    const double period = rng.uniform(1.5, 3.0);
    const double phase = rng.uniform(0.0, period);
    // Which surprise we are in, and how long ago it started.
    const double since = std::fmod(t_s + phase, period);
    const auto event = static_cast<std::uint64_t>(std::floor((t_s + phase) / period));
    cv::RNG event_rng(seed * 0xD1B54A32D192ED03ull + event * 0x94D049BB133111EBull + 3);
    const double size = event_rng.uniform(0.2, 0.45) * (event_rng.uniform(0, 2) == 0 ? -1 : 1);
    const double swing_hz = event_rng.uniform(1.2, 2.5);
    return 1 + size * std::exp(-since / 0.3) * std::cos(2 * CV_PI * swing_hz * since);
}

double metered_exposure(const cv::Mat& linear, double target, double lo, double hi) {
    const cv::Rect centre(linear.cols / 4, linear.rows / 4, linear.cols / 2, linear.rows / 2);
    const cv::Scalar m = cv::mean(linear(centre));
    const double mean = std::max(1e-3, (m[0] + m[1] + m[2]) / 3);
    return std::clamp(target / mean, lo, hi);
}

}  // namespace umf::sim
