// The field one screen shows and where: the shipped default field for the
// screen's size (field/default_field.hpp), or the screen's own field of that
// size (field_source.hpp), turned a quarter on portrait screens, centred. compose, the headless provider, the board window and the
// overlay all place the field through this, so the map in a compose MAP.json
// is the one the provider resolves points with.
#pragma once

#include <string>

#include "provider/screen/field_source.hpp"
#include "shared/field/field.hpp"
#include "shared/overlay/placement.hpp"

namespace umf::provider {

struct ScreenField {
    Field field;                     // as sent in the welcome
    std::string file;                // the file it came from: shipped, or the screen's kept one
    overlay::FieldPlacement placement;
    int screen_width = 0;
    int screen_height = 0;
};

// At `module_px` screen pixels a module (field/default_field.hpp,
// field_for_screen: the smallest shipped field that covers the screen at that
// size, or a larger module where none does); 0: the module size at which the
// default field just covers the screen. `source`: the shipped fields, or the
// screen's own. Throws std::runtime_error when the field cannot be loaded or
// made.
ScreenField screen_field_for(int screen_width, int screen_height, double module_px = 0.0,
                             const FieldSource& source = {});

// The module size a preset asks for on a screen: the preset's module_px is
// for 96 pixels an inch, so a denser screen gets more pixels a module and the
// module keeps its size in the camera's view. A density outside 50..600 ppi
// (a monitor reporting no or an absurd size) counts as 96.
double module_px_for_density(double preset_module_px, double pixels_per_inch);

// The field turned a quarter clockwise: module (i, j) of the result is module
// (h - 1 - j, i) of the original; the id gets "-r90".
Field quarter_turned(const Field& field);

}  // namespace umf::provider
