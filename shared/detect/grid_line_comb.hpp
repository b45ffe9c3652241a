// Step 3's cheapest labelling of a family's grid lines: the spacing at
// which the lines' crossings of a reference line are most periodic. Text
// strokes fall anywhere, the field's lines on a comb, so their phases add up
// at the comb's spacing however many strokes lie between them.
#pragma once

#include <span>
#include <utility>
#include <vector>

namespace umf {

// The spacings s and phases at which the weighted crossings near the image
// centre (`crossing`: pixels along the reference line from it; a Gaussian
// window) are most periodic: the peaks of the Fourier magnitude
// |sum w exp(2 pi i t / s)| within 60 % of the best, when the best stands
// clearly above the noise. A half or a third of the true spacing is just as
// periodic, and twice it may be when every other line is weak, so the caller
// judges them all. For each, the crossings near the centre labelled
// k = round((t - phase) / s).
std::vector<std::vector<std::pair<int, double>>> periodic_labellings(std::span<const double> crossing,
                                                                     std::span<const double> weight, int width,
                                                                     int height);

}  // namespace umf
