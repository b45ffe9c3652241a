// Between stages 1 and 2, a second look for faint fields: the edgels whose
// step is the field's own. Mixed in faintly, the field's module edges all
// step by about the same few grey levels (the opacity times the palette's
// contrast), while text, card borders and the screen's bezel step by far
// more; chained into lines they outnumber and outweigh the field's. When a
// search over all edgels finds nothing, the detector searches again over
// these alone.
#pragma once

#include <vector>

#include "detect/edgels.hpp"

namespace umf {

// The commonest edge step, in grey levels: the peak of the steps' histogram
// on a scale of quarter octaves. 0 with fewer than 40 edgels.
double commonest_edge_step(const std::vector<Edgel>& edgels);

// The edgels whose step lies within `spread` times of `step` either way.
std::vector<Edgel> edgels_stepping_by(const std::vector<Edgel>& edgels, double step, double spread = 2.0);

}  // namespace umf
