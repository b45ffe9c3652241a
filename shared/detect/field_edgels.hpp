// Between stages 1 and 2, the first look at a scan: the edgels whose step
// is the field's own. Mixed in faintly, the field's module edges all step
// by about the same few grey levels (the opacity times the palette's
// contrast), while text, card borders and the screen's bezel step by far
// more; chained into lines they outnumber and outweigh the field's. The
// detector searches these alone before all edgels, and when both find
// nothing, the edgels off thin lines.
#pragma once

#include <vector>

#include "shared/detect/edgels.hpp"

namespace umf {

// The commonest edge step, in grey levels: the peak of the steps' histogram
// on a scale of quarter octaves. 0 with fewer than 40 edgels.
double commonest_edge_step(const std::vector<Edgel>& edgels);

// The edgels whose step lies within `spread` times of `step` either way.
std::vector<Edgel> edgels_stepping_by(const std::vector<Edgel>& edgels, double step, double spread = 2.0);

// Whether the field's modules look a few pixels wide: along the scanlines,
// the commonest gap between consecutive field-like edgels (those stepping
// by about the commonest step) is at most 5 pixels and holds at least a
// quarter of the gaps (of at least 100). Such a far field's edges turn the
// gradients too far for the grid-line search, which then reads the
// content's grids in vain, while the lattice (lattice.hpp) finds it.
// `edgels` in the order find_edgels gives them.
bool modules_look_small(const std::vector<Edgel>& edgels);

// The edgels less those of thin lines: a table's rules, a chart's axes and
// text strokes cross a scanline as two edges of opposite sign and like
// step at most `max_width_px` apart, where the field's edges lie a module
// apart. A spreadsheet's rules run with the field's lines and, with the
// field faint, outweigh them; without them the field's lines stand out.
// `edgels` in the order find_edgels gives them (scanline by scanline).
std::vector<Edgel> edgels_off_thin_lines(const std::vector<Edgel>& edgels, double max_width_px);

}  // namespace umf
