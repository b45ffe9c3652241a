#include "screen/screen_field.hpp"

#include "field/default_field.hpp"
#include "field/field_io.hpp"

namespace umf::provider {

Field quarter_turned(const Field& field) {
    Field out = field;
    out.width = field.height;
    out.height = field.width;
    out.id = field.id + "-r90";
    for (int i = 0; i < out.height; ++i)
        for (int j = 0; j < out.width; ++j) out.at(i, j) = field.at(field.height - 1 - j, i);
    return out;
}

ScreenField screen_field_for(int screen_width, int screen_height) {
    const DefaultField choice = default_field_for_screen(screen_width, screen_height);
    ScreenField s;
    s.file = std::string(UMF_DATA_DIR) + "/fields/" + choice.file;
    s.field = load_field(s.file);
    if (choice.quarter_turn) s.field = quarter_turned(s.field);
    s.placement = overlay::centred_placement(s.field.width, s.field.height, screen_width, screen_height,
                                             choice.module_px);
    s.screen_width = screen_width;
    s.screen_height = screen_height;
    return s;
}

}  // namespace umf::provider
