#include "shared/field/verifier.hpp"

#include <stdexcept>
#include <unordered_map>

#include "shared/field/window_code.hpp"

namespace umf {

VerifyReport verify_field(const Field& field) {
    VerifyReport report;
    if (!describe_invalid(field).empty()) throw std::invalid_argument("verify: " + describe_invalid(field));
    WindowCodec codec(field.window, field.colors, field.key);
    const int rows = field.window_rows(), cols = field.window_cols();
    report.windows = field.window_count();

    // Unturned code -> windows with it, in raster order.
    std::unordered_multimap<std::uint64_t, int> by_code;
    by_code.reserve(static_cast<std::size_t>(report.windows) * 2);
    std::vector<std::uint64_t> turned(static_cast<std::size_t>(report.windows) * 4);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            int index = r * cols + c;
            for (int t = 0; t < 4; ++t) turned[index * 4 + t] = codec.code_at(field, r, c, t);
            by_code.emplace(turned[index * 4], index);
        }

    for (int b = 0; b < rows * cols; ++b) {
        const int rb = b / cols, cb = b % cols;
        // Turning by 90 degrees covers 270 too: if a window equals itself turned
        // by 90 it equals itself turned by 270, and both imply 180.
        if (turned[b * 4 + 2] == turned[b * 4])
            report.conflicts.push_back({WindowConflict::Kind::self, rb, cb, rb, cb,
                                        turned[b * 4 + 1] == turned[b * 4] ? 1 : 2});
        for (int t = 0; t < 4; ++t) {
            auto [lo, hi] = by_code.equal_range(turned[b * 4 + t]);
            for (auto it = lo; it != hi; ++it) {
                int a = it->second;
                if (a >= b) continue;  // each pair once, reported at the later window
                report.conflicts.push_back({t == 0 ? WindowConflict::Kind::duplicate : WindowConflict::Kind::rotated,
                                            a / cols, a % cols, rb, cb, t});
            }
        }
    }
    return report;
}

std::string describe(const WindowConflict& c) {
    auto at = [](int r, int col) { return "(" + std::to_string(r) + "," + std::to_string(col) + ")"; };
    switch (c.kind) {
        case WindowConflict::Kind::duplicate:
            return "window " + at(c.row_a, c.col_a) + " equals window " + at(c.row_b, c.col_b);
        case WindowConflict::Kind::rotated:
            return "window " + at(c.row_a, c.col_a) + " equals window " + at(c.row_b, c.col_b) + " turned " +
                   std::to_string(c.quarter_turns * 90) + " degrees";
        case WindowConflict::Kind::self:
            return "window " + at(c.row_a, c.col_a) + " equals itself turned " + std::to_string(c.quarter_turns * 90) +
                   " degrees";
    }
    return {};
}

}  // namespace umf
