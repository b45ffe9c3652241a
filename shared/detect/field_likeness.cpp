#include "shared/detect/field_likeness.hpp"

#include <algorithm>
#include <array>

namespace umf {

int foreign_field_windows(const ModuleGrid& grid, const VoteResult& vote, const FieldLikenessOptions& options) {
    if (vote.found || vote.votes > options.max_agreeing || grid.value.empty()) return 0;
    // Module values are 0..kMaxColors-1: counted in place, as this runs for
    // many grids of a failing frame.
    std::array<int, kMaxColors> count{};
    int known = 0;
    for (const std::int8_t v : grid.value)
        if (v >= 0 && v < kMaxColors) ++known, ++count[static_cast<std::size_t>(v)];
    const int values = static_cast<int>(std::count_if(count.begin(), count.end(), [](int n) { return n > 0; }));
    if (known < options.min_known * static_cast<double>(grid.value.size()) || values < 2) return 0;
    if (*std::max_element(count.begin(), count.end()) > options.max_value_share * known) return 0;
    return vote.windows_read;
}

}  // namespace umf
