// The content's leakage taken out of a slope image (pulse_demodulator.hpp).
// Over frames of a moving view the content does not cancel in the slope as
// it does for a camera at rest: frames taken from farther away see it
// blurrier, registrations drift by a fraction of a pixel; these change
// smoothly over the frames, as the pulse does over a window shorter than
// its period, so their part along the pulse's course stays in the slope,
// where a spreadsheet's digits then stand out white with dark rims. What
// stays is the content changed a little: to first order a blend of the
// content, its gradients and its Laplacians, with weights that change
// slowly over the view. The field does not look like those images of the
// content, so each tile's weights are fitted to the slope by least squares
// and the blend subtracted: the content's edges go, the field's modules
// stay. Measured on the tuning set's spreadsheet while the phone comes
// closer at a steep angle, its frames laid onto the newest by their true
// homographies: of 24-frame windows ending at every 4th frame from 11 to
// 79, the slope held a field the detector's whole search found in 6 of 18, the slope
// without the leakage (tiles of 240 of the 640 pixels) in 13
// (tests/detect/content_leakage_scenes_test.cpp keeps one of those windows).
#pragma once

#include <vector>

namespace umf {

// `slope` and `mean` are planes of width x height floats (the slope and the
// frames' mean, pulse_demodulator.hpp). Tiles are square, `tile` pixels a
// side (the last of a row or column smaller); each tile of `slope` has its
// own blend of the content removed, its mean with it. Throws
// std::invalid_argument for planes of another size or a tile under 8.
void remove_content_leakage(std::vector<float>& slope, const std::vector<float>& mean, int width, int height, int tile);

// A plane blurred by a Gaussian of `sigma` pixels (its tails cut at three
// sigma, the edge pixels repeated beyond the border).
std::vector<float> gaussian_blurred(const std::vector<float>& plane, int width, int height, double sigma);

}  // namespace umf
