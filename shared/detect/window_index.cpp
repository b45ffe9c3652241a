#include "shared/detect/window_index.hpp"

#include <stdexcept>
#include <string>

namespace umf {

namespace {
// Binary 4 x 4 windows and 3 x 3 edge windows (3^12) fit a table of a few MB.
constexpr std::uint64_t kTableLimit = 1u << 20;
}

WindowIndex::WindowIndex(const Field& field) : field_(field), codec_(field.window, field.colors, field.key) {
    if (auto problem = describe_invalid(field); !problem.empty())
        throw std::invalid_argument("window index: " + problem);
    const bool dense = codec_.code_space() <= kTableLimit;
    if (dense)
        table_.assign(codec_.code_space(), 0);
    else
        map_.reserve(static_cast<std::size_t>(field.window_count()) * 4);
    const int cols = field.window_cols();
    for (int r = 0; r < field.window_rows(); ++r)
        for (int c = 0; c < cols; ++c)
            for (int t = 0; t < 4; ++t) {
                const std::uint64_t code = codec_.code_at(field, r, c, t);
                const std::uint32_t entry = static_cast<std::uint32_t>((r * cols + c) * 4 + t) + 1;
                const std::uint32_t previous = dense ? table_[code] : (map_.count(code) ? map_[code] : 0);
                if (previous != 0)
                    throw std::invalid_argument("window index: field " + field.id +
                                                " is not 4-orientable (window (" + std::to_string(r) + "," +
                                                std::to_string(c) + ") repeats); run umf-field verify");
                if (dense)
                    table_[code] = entry;
                else
                    map_.emplace(code, entry);
            }
}

std::optional<WindowMatch> WindowIndex::find(std::uint64_t code) const {
    std::uint32_t entry = 0;
    if (!table_.empty()) {
        if (code >= table_.size()) return std::nullopt;
        entry = table_[code];
    } else if (auto it = map_.find(code); it != map_.end()) {
        entry = it->second;
    }
    if (entry == 0) return std::nullopt;
    const std::uint32_t e = entry - 1, w = e / 4;
    const int cols = field_.window_cols();
    return WindowMatch{static_cast<int>(w) / cols, static_cast<int>(w) % cols, static_cast<int>(e % 4)};
}

}  // namespace umf
