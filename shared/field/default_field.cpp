#include "field/default_field.hpp"

#include <algorithm>

namespace umf {

DefaultField default_field_for_screen(int width_px, int height_px) {
    struct Candidate {
        const char* file;
        int width, height;  // modules
    };
    // Smallest first: a smaller field needs fewer windows in view to place.
    static constexpr Candidate kFields[] = {{"b4-64x36.json", 64, 36}, {"b4-120x68.json", 120, 68}};
    const bool portrait = height_px > width_px;
    const int longest = std::max(width_px, height_px), shortest = std::min(width_px, height_px);
    const Candidate& c = longest <= 2560 ? kFields[0] : kFields[1];
    // Modules large enough that the field covers the whole screen.
    const int module_px = std::max((longest + c.width - 1) / c.width, (shortest + c.height - 1) / c.height);
    return {c.file, std::max(module_px, 1), portrait};
}

}  // namespace umf
