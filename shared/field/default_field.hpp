// Which shipped field a screen shows unless told otherwise. Chosen from the
// detector benchmark (docs/BENCHMARKS.md, "Default field"): binary fields
// with 4 x 4 windows read best at low opacity, because each module carries
// the whole contrast the overlay may use, where 3 or 5 shades split it; at
// 30 screen pixels a module stays at least 6 camera pixels wide from a
// 640 x 480 phone at 60 cm from a 24" screen.
#pragma once

#include <string>

namespace umf {

struct DefaultField {
    std::string file;           // in shared/data/fields
    int module_px = 0;          // screen pixels per module
    bool quarter_turn = false;  // portrait screens show the field turned by 90 degrees
};

// The field for a screen of the given pixel size at the module size that
// covers it: b4-64x36 for screens up to 2560 pixels wide (1920 x 1080 is
// covered exactly at 30 px), b4-120x68 beyond (3840 x 2160 exactly at 32 px).
// A field turned a quarter is as unique as the field, so portrait screens
// show it turned.
DefaultField default_field_for_screen(int width_px, int height_px);

// The field for a screen at a wanted module size (whole pixels, at least 1):
// the smallest shipped binary field (b4-64x36, b4-96x54, b4-120x68) that
// covers the screen at that size; it may reach past the screen's edges. When
// even the largest does not, the largest at the module size that covers the
// screen, which is then larger than wanted. wanted_module_px <= 0 gives
// default_field_for_screen.
DefaultField field_for_screen(int width_px, int height_px, double wanted_module_px);

}  // namespace umf
