#include "shared/detect/pulse_demodulator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shared/detect/content_leakage.hpp"

namespace umf {

PulseDemodulator::PulseDemodulator(double forget) : forget_(std::clamp(forget, 0.0, 0.99)) {}

void PulseDemodulator::reset() {
    width_ = height_ = frames_ = 0;
    weight_ = sum_a_ = sum_aa_ = 0;
    sum_i_.clear();
    sum_ai_.clear();
}

void PulseDemodulator::add(const GreyView& frame, double opacity) {
    if (auto problem = describe_invalid(frame); !problem.empty())
        throw std::invalid_argument("pulse demodulation: " + problem);
    if (!(opacity >= 0 && opacity <= 1))
        throw std::invalid_argument("pulse demodulation: opacity " + std::to_string(opacity) + " is not in [0, 1]");
    if (frame.width != width_ || frame.height != height_) {
        reset();
        width_ = frame.width;
        height_ = frame.height;
        sum_i_.assign(static_cast<std::size_t>(width_) * height_, 0.f);
        sum_ai_.assign(sum_i_.size(), 0.f);
    }
    const float keep = static_cast<float>(1 - forget_);
    const float a = static_cast<float>(opacity);
    ++frames_;
    weight_ = weight_ * keep + 1;
    sum_a_ = sum_a_ * keep + opacity;
    sum_aa_ = sum_aa_ * keep + opacity * opacity;
    for (int y = 0; y < height_; ++y) {
        const std::uint8_t* in = frame.row(y);
        float* si = sum_i_.data() + static_cast<std::size_t>(y) * width_;
        float* sai = sum_ai_.data() + static_cast<std::size_t>(y) * width_;
        for (int x = 0; x < width_; ++x) {
            si[x] = si[x] * keep + in[x];
            sai[x] = sai[x] * keep + a * in[x];
        }
    }
}

double PulseDemodulator::opacity_spread() const {
    if (weight_ <= 0) return 0;
    const double mean = sum_a_ / weight_;
    return std::sqrt(std::max(0.0, sum_aa_ / weight_ - mean * mean));
}

// Least squares per pixel: slope = (W Σ aI - Σa ΣI) / (W Σa² - (Σa)²), the
// two factors k and m of slope = k Σ aI - m Σ I; none before two opacities.
std::optional<std::pair<double, double>> PulseDemodulator::slope_terms() const {
    const double det = weight_ * sum_aa_ - sum_a_ * sum_a_;
    if (frames_ < 2 || !(det > 1e-12 * weight_ * weight_)) return std::nullopt;
    return std::pair{weight_ / det, sum_a_ / det};
}

GreyView PulseDemodulator::field_image(SlopeScale scale) {
    const auto terms = slope_terms();
    if (!terms) return {};
    // The two products nearly cancel: their difference in double.
    double k = terms->first / 2, m = terms->second / 2;
    if (scale == SlopeScale::spread) {
        double magnitude = 0;
        for (std::size_t i = 0; i < sum_i_.size(); ++i) magnitude += std::abs(k * sum_ai_[i] - m * sum_i_[i]);
        magnitude /= static_cast<double>(sum_i_.size());
        if (!(magnitude > 0)) return {};
        k *= kSpreadLevels / magnitude;
        m *= kSpreadLevels / magnitude;
    }
    image_.resize(sum_i_.size());
    for (std::size_t i = 0; i < image_.size(); ++i) {
        const double half_slope = k * sum_ai_[i] - m * sum_i_[i];
        image_[i] = static_cast<std::uint8_t>(std::clamp(127.5 + half_slope, 0.0, 255.0) + 0.5);  // rounded
    }
    return {image_.data(), width_, height_, width_};
}

GreyView PulseDemodulator::content_free_field_image(int tile) {
    const auto terms = slope_terms();
    if (!terms) return {};
    const auto [k, m] = *terms;
    std::vector<float> slope(sum_i_.size()), mean(sum_i_.size());
    for (std::size_t i = 0; i < slope.size(); ++i) {
        slope[i] = static_cast<float>(k * sum_ai_[i] - m * sum_i_[i]);
        mean[i] = static_cast<float>(sum_i_[i] / weight_);
    }
    remove_content_leakage(slope, mean, width_, height_, tile);
    double magnitude = 0;
    for (const float v : slope) magnitude += std::abs(v);
    magnitude /= static_cast<double>(slope.size());
    if (!(magnitude > 0)) return {};
    const double scale = kSpreadLevels / magnitude;
    image_.resize(slope.size());
    for (std::size_t i = 0; i < image_.size(); ++i)
        image_[i] = static_cast<std::uint8_t>(std::clamp(127.5 + scale * slope[i], 0.0, 255.0) + 0.5);
    return {image_.data(), width_, height_, width_};
}

GreyView PulseDemodulator::full_opacity_image(double opacity_at_zero, double opacity_at_one) {
    const double det = weight_ * sum_aa_ - sum_a_ * sum_a_;
    const double range = opacity_at_one - opacity_at_zero;
    if (frames_ < 2 || !(det > 1e-12 * weight_ * weight_) || !(std::abs(range) > 1e-6)) return {};
    // The line's value at the given value `one` that is opacity 1: the mean
    // plus the slope times the way from the mean there, in the sums.
    const double one = (1 - opacity_at_zero) / range, from_mean = one - sum_a_ / weight_;
    const double p = from_mean * weight_ / det, q = 1 / weight_ - from_mean * sum_a_ / det;
    image_.resize(sum_i_.size());
    for (std::size_t i = 0; i < image_.size(); ++i)
        image_[i] = static_cast<std::uint8_t>(std::clamp(p * sum_ai_[i] + q * sum_i_[i], 0.0, 255.0) + 0.5);
    return {image_.data(), width_, height_, width_};
}

}  // namespace umf
