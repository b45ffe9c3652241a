// Edge contrast of a field: how clearly neighbouring modules differ. The
// detector of k-ary fields reads edges, so an edge between equal modules is
// invisible and small steps between shades are easy to misread.
#pragma once

#include "shared/field/field.hpp"

namespace umf {

struct EdgeContrast {
    long edges = 0;
    long flat_edges = 0;      // between equal modules
    double mean_step = 0;     // mean |difference| / (colors - 1), in [0, 1]
    double flat_fraction() const { return edges ? static_cast<double>(flat_edges) / edges : 0; }
};

EdgeContrast edge_contrast(const Field& field);

// The score the generator maximises for one edge: the step between the two
// shades, and a flat edge costs twice what a full-range step gains.
inline int edge_score(int a, int b, int colors) {
    int d = a > b ? a - b : b - a;
    return d == 0 ? -2 * (colors - 1) : d;
}

}  // namespace umf
