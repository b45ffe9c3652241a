// What happens to the light between the screen and the phone's JPEG, apart
// from geometry. The simulator works in linear light (float, 0 = black,
// 1 = the screen's white) because blur, glare and exposure act on light, not
// on pixel values; images enter and leave through a 2.2 power law, so a shot
// without degradation reproduces the screen's pixel values exactly.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace umf::sim {

struct Degradation {
    double defocus_sigma_px = 0;   // Gaussian blur in image pixels
    double motion_blur_px = 0;     // length of the straight smear in image pixels
    double motion_angle_deg = 0;   // its direction, 0 = along the image's x axis, clockwise towards +y
    double noise_sigma = 0;        // Gaussian noise in grey levels of the 8-bit output, per channel
    double exposure = 1.0;         // multiplies the light; > 1 over-exposes and clips
    double gamma = 1.0;            // extra power on the camera's output values; > 1 darkens mid-tones
    double glare = 0;              // 0..1: peak of a bright reflection blob, as a fraction of the screen's white
    bool subpixels = false;        // the screen shows R, G, B stripes per pixel (moire at some distances)
    // The screen's pixel grid up close: R, G, B stripes and a dark row of
    // black matrix under each pixel row, sampled with two octaves of detail
    // let through unfiltered (strong moire where a screen pixel is about an
    // image pixel). Takes the place of subpixels.
    bool pixel_grid = false;
    int jpeg_quality = 0;          // 0 = no JPEG
    std::uint64_t seed = 1;        // noise and glare position
};

// 8-bit BGR values to linear light, CV_32FC3.
cv::Mat to_linear(const cv::Mat& bgr8);
cv::Vec3f to_linear(const cv::Vec3b& bgr);

// Linear light to 8-bit BGR values through the camera's tone curve
// (the inverse of to_linear, then the extra gamma), with noise added in
// output values before rounding, as a camera's noise shows in its output.
cv::Mat to_output(const cv::Mat& linear, double gamma, double noise_sigma, std::uint64_t seed);

// The screen as seen through a magnifier: each pixel becomes three stripes,
// R, G, B from left to right, each three times as bright in its channel, so
// the average over the pixel is unchanged. Three times as wide as the input.
cv::Mat subpixel_stripes(const cv::Mat& linear);

// Each pixel as a 3 x 3 block: R, G, B columns in its upper two rows, each
// 4.5 times as bright in its channel, and a black bottom row (the black
// matrix between pixel rows), so the average over the pixel is unchanged.
// Three times as wide and as tall as the input.
cv::Mat pixel_grid(const cv::Mat& linear);

// A normalised kernel smearing along a straight line (sub-pixel accurate, so
// fractional lengths make a difference).
cv::Mat motion_kernel(double length_px, double angle_deg);

// Defocus and motion blur, in place, on linear light.
void apply_optics(cv::Mat& linear, const Degradation& degradation);

// Adds a broad bright blob at a seeded position, as a lamp reflected in the
// screen would, in place.
void apply_glare(cv::Mat& linear, double strength, std::uint64_t seed);

// Encodes and decodes as JPEG at the given quality (1..100).
cv::Mat jpeg_roundtrip(const cv::Mat& bgr8, int quality);

}  // namespace umf::sim
