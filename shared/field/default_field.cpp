#include "shared/field/default_field.hpp"

#include <algorithm>
#include <cmath>

namespace umf {

namespace {

struct Candidate {
    const char* file;
    int width, height;  // modules
};

// Smallest first: a smaller field needs fewer windows in view to place.
constexpr Candidate kFields[] = {{"b4-64x36.json", 64, 36}, {"b4-96x54.json", 96, 54}, {"b4-120x68.json", 120, 68}};
constexpr Candidate kSmallest = kFields[0];
constexpr Candidate kLargest = kFields[2];

// Whole pixels per module at which `c` covers a screen whose longer side is
// `longest` and shorter `shortest` (the field's longer side along the screen's).
int covering_module(const Candidate& c, int longest, int shortest) {
    return std::max({(longest + c.width - 1) / c.width, (shortest + c.height - 1) / c.height, 1});
}

}  // namespace

DefaultField default_field_for_screen(int width_px, int height_px) {
    const bool portrait = height_px > width_px;
    const int longest = std::max(width_px, height_px), shortest = std::min(width_px, height_px);
    const Candidate& c = longest <= 2560 ? kSmallest : kLargest;
    return {c.file, covering_module(c, longest, shortest), portrait};
}

DefaultField field_for_screen(int width_px, int height_px, double wanted_module_px) {
    if (!(wanted_module_px > 0) || !std::isfinite(wanted_module_px)) return default_field_for_screen(width_px, height_px);
    const bool portrait = height_px > width_px;
    const int longest = std::max(width_px, height_px), shortest = std::min(width_px, height_px);
    const int wanted = std::max(1, static_cast<int>(std::lround(std::min(wanted_module_px, 1e6))));
    for (const Candidate& c : kFields)
        if (covering_module(c, longest, shortest) <= wanted) return {c.file, wanted, portrait};
    return {kLargest.file, covering_module(kLargest, longest, shortest), portrait};
}

}  // namespace umf
