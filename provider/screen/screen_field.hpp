// The field one screen shows and where: the shipped default field for the
// screen's size (field/default_field.hpp), turned a quarter on portrait
// screens, centred at the module size that covers the screen. compose, the
// headless provider and the overlay all place the field through this, so the
// map in a compose MAP.json is the one the provider resolves points with.
#pragma once

#include <string>

#include "field/field.hpp"
#include "overlay/placement.hpp"

namespace umf::provider {

struct ScreenField {
    Field field;                     // as sent in the welcome
    std::string file;                // the shipped file it came from
    overlay::FieldPlacement placement;
    int screen_width = 0;
    int screen_height = 0;
};

// Throws std::runtime_error when the shipped field cannot be loaded.
ScreenField screen_field_for(int screen_width, int screen_height);

// The field turned a quarter clockwise: module (i, j) of the result is module
// (h - 1 - j, i) of the original; the id gets "-r90".
Field quarter_turned(const Field& field);

}  // namespace umf::provider
