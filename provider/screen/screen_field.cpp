#include "provider/screen/screen_field.hpp"

#include <cmath>

#include "provider/common/install_paths.hpp"
#include "shared/field/default_field.hpp"
#include "shared/field/field_io.hpp"

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

ScreenField screen_field_for(int screen_width, int screen_height, double module_px, const FieldSource& source) {
    const DefaultField choice = field_for_screen(screen_width, screen_height, module_px);
    ScreenField s;
    FieldSource::Chosen chosen = source.field_for((shipped_fields_dir() / choice.file).string());
    s.file = std::move(chosen.file);
    s.field = std::move(chosen.field);
    if (choice.quarter_turn) s.field = quarter_turned(s.field);
    s.placement = overlay::centred_placement(s.field.width, s.field.height, screen_width, screen_height,
                                             choice.module_px);
    s.screen_width = screen_width;
    s.screen_height = screen_height;
    return s;
}

double module_px_for_density(double preset_module_px, double pixels_per_inch) {
    constexpr double kReferencePpi = 96.0;
    const bool plausible = std::isfinite(pixels_per_inch) && pixels_per_inch >= 50.0 && pixels_per_inch <= 600.0;
    return preset_module_px * (plausible ? pixels_per_inch : kReferencePpi) / kReferencePpi;
}

}  // namespace umf::provider
