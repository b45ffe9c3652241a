#include "shared/detect/module_grid.hpp"

namespace umf {

void ModuleGrid::derive_edges() {
    auto sign = [](int d) { return static_cast<std::int8_t>((d > 0) - (d < 0)); };
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const std::int8_t v = at(i, j);
            if (j + 1 < cols) right_of(i, j) = (v == kUnknown || at(i, j + 1) == kUnknown) ? kUnknown : sign(at(i, j + 1) - v);
            if (i + 1 < rows) below(i, j) = (v == kUnknown || at(i + 1, j) == kUnknown) ? kUnknown : sign(at(i + 1, j) - v);
        }
}

ModuleGrid ModuleGrid::crop(int i0, int j0, int rows_, int cols_) const {
    ModuleGrid out(rows_, cols_);
    for (int i = 0; i < rows_; ++i)
        for (int j = 0; j < cols_; ++j) {
            const int a = i0 + i, b = j0 + j;
            if (a < 0 || b < 0 || a >= rows || b >= cols) continue;
            out.at(i, j) = at(a, b);
            out.right_of(i, j) = j + 1 < cols_ ? right_of(a, b) : kUnknown;
            out.below(i, j) = i + 1 < rows_ ? below(a, b) : kUnknown;
        }
    return out;
}

std::optional<std::uint64_t> observed_code(const ModuleGrid& g, const WindowCodec& codec, int i, int j) {
    const int n = codec.window();
    if (i < 0 || j < 0 || i + n > g.rows || j + n > g.cols) return std::nullopt;
    std::uint64_t code = 0;
    if (codec.key() == WindowKey::modules) {
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                const std::int8_t v = g.at(i + a, j + b);
                if (v < 0 || v >= codec.colors()) return std::nullopt;
                code += static_cast<std::uint64_t>(v) * codec.place(a * n + b);
            }
        return code;
    }
    // Digit order of WindowCodec: horizontal edges row-major, then vertical edges.
    int d = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b + 1 < n; ++b, ++d) {
            const std::int8_t s = g.right_of(i + a, j + b);
            if (s < -1 || s > 1) return std::nullopt;
            code += static_cast<std::uint64_t>(s + 1) * codec.place(d);
        }
    for (int a = 0; a + 1 < n; ++a)
        for (int b = 0; b < n; ++b, ++d) {
            const std::int8_t s = g.below(i + a, j + b);
            if (s < -1 || s > 1) return std::nullopt;
            code += static_cast<std::uint64_t>(s + 1) * codec.place(d);
        }
    return code;
}

}  // namespace umf
