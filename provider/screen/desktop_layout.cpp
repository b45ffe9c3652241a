#include "screen/desktop_layout.hpp"

#include <algorithm>
#include <climits>
#include <stdexcept>

namespace umf::provider {

DesktopLayout lay_out_desktop(const std::vector<DesktopScreen>& screens) {
    if (screens.empty()) throw std::invalid_argument("a desktop needs at least one screen");
    int left = INT_MAX, top = INT_MAX, right = INT_MIN, bottom = INT_MIN;
    for (std::size_t i = 0; i < screens.size(); ++i) {
        const auto& s = screens[i];
        if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
            throw std::invalid_argument("screen \"" + s.name + "\" has no usable size");
        for (std::size_t j = 0; j < i; ++j) {
            const auto& o = screens[j];
            if (s.x < o.x + o.width && o.x < s.x + s.width && s.y < o.y + o.height && o.y < s.y + s.height)
                throw std::invalid_argument("screens \"" + o.name + "\" and \"" + s.name +
                                            "\" overlap (mirrored screens show one field; turn mirroring off)");
        }
        left = std::min(left, s.x);
        top = std::min(top, s.y);
        right = std::max(right, s.x + s.width);
        bottom = std::max(bottom, s.y + s.height);
    }
    // The field for the bounding box, as if it were one screen.
    const ScreenField whole = screen_field_for(right - left, bottom - top);
    DesktopLayout layout;
    layout.field = whole.field;
    layout.file = whole.file;
    for (const auto& s : screens) {
        LaidOutScreen laid;
        laid.screen = s;
        laid.field = whole;
        laid.field.screen_width = s.width;
        laid.field.screen_height = s.height;
        // The same placement, seen from this screen's top-left corner.
        laid.field.placement.origin_x = whole.placement.origin_x + left - s.x;
        laid.field.placement.origin_y = whole.placement.origin_y + top - s.y;
        const auto area = overlay::visible_area(laid.field.placement, whole.field.width, whole.field.height, s.width,
                                                s.height);
        if (!area) throw std::invalid_argument("the field does not reach screen \"" + s.name + "\"");
        laid.region = *area;
        layout.screens.push_back(std::move(laid));
    }
    return layout;
}

}  // namespace umf::provider
