#include "provider/commands/preset_options.hpp"

#include "shared/field/field.hpp"

namespace umf::provider {

using cli::get;
using cli::UsageError;

overlay::Preset preset_option(const cli::Args& a, const std::filesystem::path& config_dir, bool board) {
    std::vector<overlay::Preset> presets = overlay::built_in_presets();
    const auto user_file = config_dir / "presets.json";
    std::error_code ec;
    if (std::filesystem::exists(user_file, ec))
        for (auto& p : overlay::load_presets(user_file.string())) presets.push_back(std::move(p));
    // Boards and kiosks are there to be pointed at: their field is always up.
    const std::string name = get(a, "preset").value_or(board ? "kiosk" : "balanced");
    // User presets come last and win over a built-in of the same name.
    for (auto it = presets.rbegin(); it != presets.rend(); ++it)
        if (it->name == name) return *it;
    std::string names;
    for (const auto& p : presets) names += (names.empty() ? "" : ", ") + p.name;
    throw UsageError("no preset called \"" + name + "\"; there are " + names);
}

const std::vector<std::string>& preset_setting_options() {
    static const std::vector<std::string> kOptions = {"opacity-min", "opacity-max", "period",     "waveform",
                                                      "module-px",   "blur",        "region",     "focus-radius",
                                                      "activation",  "fade",        "palette"};
    return kOptions;
}

overlay::Preset apply_preset_options(overlay::Preset p, const cli::Args& a) {
    if (auto v = get(a, "opacity-min")) p.opacity_min = cli::to_number("opacity-min", *v, 0.0, 1.0);
    if (auto v = get(a, "opacity-max")) p.opacity_max = cli::to_number("opacity-max", *v, 0.0, 1.0);
    if (auto v = get(a, "period")) p.period_s = cli::to_number("period", *v, 0.0, overlay::kMaxPeriodS);
    if (auto v = get(a, "module-px"))
        p.module_px = cli::to_number("module-px", *v, overlay::kMinModulePx, overlay::kMaxModulePx);
    if (auto v = get(a, "blur")) p.blur = cli::to_number("blur", *v, 0.0, 1.0);
    if (auto v = get(a, "focus-radius"))
        p.focus_radius_modules = cli::to_number("focus-radius", *v, 1.0, overlay::kMaxFocusRadiusModules);
    if (auto v = get(a, "fade")) p.fade_s = cli::to_number("fade", *v, 0.0, overlay::kMaxFadeS);
    if (auto v = get(a, "waveform")) {
        const auto w = overlay::waveform_from_string(*v);
        if (!w) throw UsageError("--waveform is sine or triangle, not " + *v);
        p.waveform = *w;
    }
    if (auto v = get(a, "region")) {
        const auto r = overlay::region_from_string(*v);
        if (!r) throw UsageError("--region is full or focus, not " + *v);
        p.region = *r;
    }
    if (auto v = get(a, "activation")) {
        const auto act = overlay::activation_from_string(*v);
        if (!act) throw UsageError("--activation is always or on_demand, not " + *v);
        p.activation = *act;
    }
    if (auto v = get(a, "palette")) {
        // "#000000,#ffffff": one colour per field colour, dark to light.
        std::vector<std::string> palette;
        std::size_t start = 0;
        for (;;) {
            const auto comma = v->find(',', start);
            palette.push_back(v->substr(start, comma == std::string::npos ? std::string::npos : comma - start));
            if (!is_hex_colour(palette.back())) throw UsageError("--palette takes #rrggbb colours separated by commas");
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
        p.palette = std::move(palette);
    }
    if (const std::string problem = overlay::describe_invalid(p); !problem.empty())
        throw UsageError("the preset's settings do not fit together: " + problem);
    return p;
}

}  // namespace umf::provider
