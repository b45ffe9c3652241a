// The field's module edges, row by row: where two neighbouring modules
// differ in brightness, the refit (refine.hpp) looks for an edge in the
// image. The field does not change from frame to frame, so its edges are
// listed once, with the detector, and each ring of the refit takes its
// share by binary search instead of walking every module inside it.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "shared/detect/homography.hpp"
#include "shared/field/field.hpp"

namespace umf {

// A module edge the field predicts: its midpoint in field coordinates, the
// field direction across it (towards the brighter side when polarity > 0).
struct ExpectedEdge {
    Point2 mid;
    Point2 across;
    double polarity;  // +1: brighter on the +across side, -1: darker
};

// Brightness of each module value as the image shows it: the luma of the
// field's palette, or the value itself for the grey default.
std::vector<double> module_brightness(const Field& field);

class ModuleEdges {
public:
    explicit ModuleEdges(const Field& field);

    // The edges of the modules in rows r0..r1 and columns c0..c1 (inclusive,
    // inside the field): the edge on each module's left (from column 1 on),
    // then the one above it (from row 1 on), module by module in row-major
    // order; when there are more than `most`, every k-th of them, spread
    // evenly from the first.
    void spread_within(int r0, int r1, int c0, int c1, std::size_t most, std::vector<ExpectedEdge>& out) const;

private:
    struct Entry {
        int col;
        ExpectedEdge edge;
    };
    // Row r's entries of columns c0..c1: [first, second) in entries_.
    std::pair<std::size_t, std::size_t> run(int r, int c0, int c1) const;

    std::vector<Entry> entries_;          // row by row, columns ascending
    std::vector<std::size_t> row_start_;  // rows + 1 offsets into entries_
};

}  // namespace umf
