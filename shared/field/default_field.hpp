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
    int module_px = 0;          // screen pixels per module at which it covers the screen
    bool quarter_turn = false;  // portrait screens show the field turned by 90 degrees
};

// The field for a screen of the given pixel size: b4-64x36 at 30 px for
// screens up to 2560 pixels wide (1920 x 1080 is covered exactly), b4-120x68
// at 32 px beyond (3840 x 2160 exactly). A field turned a quarter is as
// unique as the field, so portrait screens show it turned.
DefaultField default_field_for_screen(int width_px, int height_px);

}  // namespace umf
