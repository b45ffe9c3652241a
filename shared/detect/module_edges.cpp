#include "shared/detect/module_edges.hpp"

#include <algorithm>
#include <cstdlib>

namespace umf {

std::vector<double> module_brightness(const Field& f) {
    std::vector<double> out(static_cast<std::size_t>(f.colors));
    for (int k = 0; k < f.colors; ++k) {
        out[k] = k;
        if (k < static_cast<int>(f.palette.size()) && f.palette[k].size() == 7 && f.palette[k][0] == '#') {
            const long rgb = std::strtol(f.palette[k].c_str() + 1, nullptr, 16);
            out[k] = 0.299 * ((rgb >> 16) & 255) + 0.587 * ((rgb >> 8) & 255) + 0.114 * (rgb & 255);
        }
    }
    return out;
}

ModuleEdges::ModuleEdges(const Field& f) {
    const std::vector<double> brightness = module_brightness(f);
    row_start_.reserve(static_cast<std::size_t>(f.height) + 1);
    for (int r = 0; r < f.height; ++r) {
        row_start_.push_back(entries_.size());
        for (int c = 0; c < f.width; ++c) {
            const double here = brightness[f.at(r, c)];
            if (c > 0) {  // the edge on the module's left
                const double d = here - brightness[f.at(r, c - 1)];
                if (d != 0) entries_.push_back({c, {Point2(c, r + 0.5), Point2(1, 0), d > 0 ? 1.0 : -1.0}});
            }
            if (r > 0) {  // the edge above it
                const double d = here - brightness[f.at(r - 1, c)];
                if (d != 0) entries_.push_back({c, {Point2(c + 0.5, r), Point2(0, 1), d > 0 ? 1.0 : -1.0}});
            }
        }
    }
    row_start_.push_back(entries_.size());
}

std::pair<std::size_t, std::size_t> ModuleEdges::run(int r, int c0, int c1) const {
    const auto by_col = [](const Entry& e, int c) { return e.col < c; };
    const auto first = entries_.begin() + static_cast<std::ptrdiff_t>(row_start_[static_cast<std::size_t>(r)]);
    const auto last = entries_.begin() + static_cast<std::ptrdiff_t>(row_start_[static_cast<std::size_t>(r) + 1]);
    const auto b = std::lower_bound(first, last, c0, by_col);
    const auto e = std::lower_bound(b, last, c1 + 1, by_col);
    return {static_cast<std::size_t>(b - entries_.begin()), static_cast<std::size_t>(e - entries_.begin())};
}

void ModuleEdges::spread_within(int r0, int r1, int c0, int c1, std::size_t most,
                                std::vector<ExpectedEdge>& out) const {
    out.clear();
    if (r0 > r1 || c0 > c1) return;
    // Each row's share is one run of its entries: the runs are counted
    // first, for the stride, then every stride-th entry taken across them
    // (two binary searches a row each time, and nothing allocated per call).
    std::size_t total = 0;
    for (int r = r0; r <= r1; ++r) {
        const auto [b, e] = run(r, c0, c1);
        total += e - b;
    }
    const std::size_t stride = std::max<std::size_t>(1, (total + most - 1) / std::max<std::size_t>(1, most));
    std::size_t skip = 0;  // entries to pass over before the next one taken
    for (int r = r0; r <= r1; ++r) {
        const auto [b, e] = run(r, c0, c1);
        std::size_t i = b + skip;
        for (; i < e; i += stride) out.push_back(entries_[i].edge);
        skip = i - e;
    }
}

}  // namespace umf
