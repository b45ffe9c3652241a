// The screen's physical pixel structure as a camera sees it: each screen
// pixel is not a uniform square but sub-pixel emitters (red, green, blue)
// separated by the black matrix. Close up the camera resolves stripes and
// the dark grid; at middle distances its sensor samples the fine structure
// without an optical low-pass filter and aliases it into moire.
//
// Rendered as a per-channel gain on the (antialiased) screen light: the
// structure's emission averaged over each image pixel's footprint, from a
// few point samples per image pixel taken *before* any optical blur, as a
// sensor does. The gain averages 1 per channel over a whole screen pixel
// (a 2 x 2 tile for PenTile), so where the camera cannot resolve the
// structure and nothing aliases, the picture keeps its brightness.
#pragma once

#include <opencv2/core.hpp>

namespace umf::sim {

enum class PixelLayout {
    rgb_stripe,  // LCD: R, G, B columns per pixel, black matrix around each
    pentile,     // OLED diamond (RGBG): every pixel has green, red and blue alternate
};

const char* to_string(PixelLayout layout);

struct PixelStructure {
    PixelLayout layout = PixelLayout::rgb_stripe;
    double fill = 0.7;  // emitting share of each sub-pixel cell's width and height (1 = no black matrix)
    int samples = 3;    // point samples per image pixel and axis (3 = 9 samples: little prefiltering)
};

// Emission of channel c (0 = B, 1 = G, 2 = R, OpenCV order) at a continuous
// screen point, normalised so the mean over a layout's tile is 1.
float structure_emission(const PixelStructure& structure, cv::Point2d screen_px, int channel);

// CV_32FC3 of the image's size: the mean emission per channel over the
// image pixel's point samples. image_to_screen maps continuous image
// coordinates to continuous screen coordinates.
cv::Mat structure_gain(const PixelStructure& structure, const cv::Matx33d& image_to_screen, cv::Size image);

}  // namespace umf::sim
