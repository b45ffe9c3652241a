#include "shared/overlay/placement.hpp"

#include <algorithm>
#include <cmath>

namespace umf::overlay {

FieldPlacement centred_placement(int field_width, int field_height, int screen_width, int screen_height,
                                 double module_px) {
    FieldPlacement p;
    p.module_px = module_px;
    p.origin_x = std::floor((screen_width - field_width * module_px) / 2.0);
    p.origin_y = std::floor((screen_height - field_height * module_px) / 2.0);
    return p;
}

std::optional<FieldArea> visible_area(const FieldPlacement& p, int field_width, int field_height, int screen_width,
                                      int screen_height) {
    FieldArea a;
    screen_to_field(p, 0.0, 0.0, a.u0, a.v0);
    screen_to_field(p, screen_width, screen_height, a.u1, a.v1);
    a.u0 = std::max(a.u0, 0.0);
    a.v0 = std::max(a.v0, 0.0);
    a.u1 = std::min(a.u1, static_cast<double>(field_width));
    a.v1 = std::min(a.v1, static_cast<double>(field_height));
    if (!(a.u0 < a.u1 && a.v0 < a.v1)) return std::nullopt;
    return a;
}

}  // namespace umf::overlay
