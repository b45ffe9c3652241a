// What a phone's image processor does to a frame after the sensor: noise
// reduction that smooths faint texture away, sharpening with halos beside
// every edge (unsharp masking), local tone mapping that lifts dark regions and
// tames bright ones, and auto-exposure that hunts when a bright screen comes
// into view (it overshoots, then settles in a damped swing).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

namespace umf::sim {

struct PhoneProcessing {
    double denoise = 0;            // edge-preserving smoothing strength in grey levels (bilateral sigma); 0 = off
    double sharpen_amount = 0;     // unsharp mask: out = in + amount * (in - blur(in)); 0 = off
    double sharpen_sigma_px = 1.5;
    double local_tone = 0;         // 0..1: how far large-scale brightness differences are evened out
};

// The processing on an 8-bit BGR frame, in that order: denoise, local tone
// mapping, sharpening. Deterministic.
cv::Mat process_phone_frame(const cv::Mat& bgr8, const PhoneProcessing& processing);

// Unsharp mask alone (8-bit BGR), for tests and reuse.
cv::Mat unsharp_mask(const cv::Mat& bgr8, double amount, double sigma_px);

// Local tone mapping alone: each pixel scaled by (global mean / local mean)
// ^ strength of the brightness around it (a Gaussian of a sixteenth of the
// image width), so regions move towards the average and detail stays.
cv::Mat local_tone_map(const cv::Mat& bgr8, double strength);

// Auto-exposure hunting: a factor on the metered exposure at time t_s. Every
// `period_s` (seeded between 1.5 and 3 s) the metering is surprised by the
// screen and swings, starting 20..45 % off and decaying with a time constant
// of about 0.3 s. 1 = settled.
double exposure_hunt(double t_s, std::uint64_t seed);

// The exposure a phone's metering picks: scales linear light so that the
// mean of the central half of the frame becomes `target`, within [lo, hi].
double metered_exposure(const cv::Mat& linear, double target, double lo, double hi);

}  // namespace umf::sim
