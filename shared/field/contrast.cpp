#include "shared/field/contrast.hpp"

#include <cstdlib>

namespace umf {

EdgeContrast edge_contrast(const Field& f) {
    EdgeContrast out;
    long step_sum = 0;
    auto visit = [&](int a, int b) {
        int d = std::abs(a - b);
        ++out.edges;
        out.flat_edges += d == 0;
        step_sum += d;
    };
    for (int r = 0; r < f.height; ++r)
        for (int c = 0; c < f.width; ++c) {
            if (c + 1 < f.width) visit(f.at(r, c), f.at(r, c + 1));
            if (r + 1 < f.height) visit(f.at(r, c), f.at(r + 1, c));
        }
    if (out.edges && f.colors > 1) out.mean_step = static_cast<double>(step_sum) / out.edges / (f.colors - 1);
    return out;
}

}  // namespace umf
