// Where a field lies on a screen (docs/PROTOCOL.md, "Coordinates"): screen
// pixel = origin + module_px * (u, v), with continuous pixel coordinates
// (pixel (x, y) covers [x, x + 1) x [y, y + 1)). The provider alone knows
// this map; requesters speak field points.
#pragma once

#include <optional>

namespace umf::overlay {

struct FieldPlacement {
    double origin_x = 0.0;  // screen position of field point (0, 0)
    double origin_y = 0.0;
    double module_px = 30.0;  // > 0
    bool operator==(const FieldPlacement&) const = default;
};

struct PixelPoint {
    double x = 0.0;
    double y = 0.0;
};

// A rectangle of field points: u0 <= u < u1, v0 <= v < v1.
struct FieldArea {
    double u0 = 0.0, v0 = 0.0, u1 = 0.0, v1 = 0.0;
    bool contains(double u, double v) const { return u >= u0 && u < u1 && v >= v0 && v < v1; }
};

inline PixelPoint field_to_screen(const FieldPlacement& p, double u, double v) {
    return {p.origin_x + p.module_px * u, p.origin_y + p.module_px * v};
}
inline void screen_to_field(const FieldPlacement& p, double x, double y, double& u, double& v) {
    u = (x - p.origin_x) / p.module_px;
    v = (y - p.origin_y) / p.module_px;
}

// A field of field_width x field_height modules at module_px, centred on a
// screen of screen_width x screen_height pixels, its origin on whole pixels
// so that module edges fall where a compositor draws them.
FieldPlacement centred_placement(int field_width, int field_height, int screen_width, int screen_height,
                                 double module_px);

// The field points the screen shows: the field's rectangle clipped to the
// screen's; nullopt when they do not meet.
std::optional<FieldArea> visible_area(const FieldPlacement& p, int field_width, int field_height, int screen_width,
                                      int screen_height);

}  // namespace umf::overlay
