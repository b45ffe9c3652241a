#include "shared/overlay/preset.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>

#include "shared/field/field.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::overlay {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw PresetError(where + ": " + what); }

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

// "must be 0..1, not 1.5" for a member outside [lo, hi] (NaN included).
std::string outside(const char* member, double v, double lo, double hi) {
    if (v >= lo && v <= hi) return {};
    return std::string("\"") + member + "\" must be " + number_text(lo) + ".." + number_text(hi) + ", not " +
           number_text(v);
}

const std::set<std::string>& known_members() {
    static const std::set<std::string> names = {
        "name",    "opacity_min", "opacity_max", "period_s",             "waveform",   "module_px",
        "palette", "blur",        "region",      "focus_radius_modules", "activation", "fade_s"};
    return names;
}

double number_member(const json& doc, const char* name, double fallback, const std::string& where) {
    auto it = doc.find(name);
    if (it == doc.end()) return fallback;
    if (!it->is_number()) fail(where, std::string("\"") + name + "\" must be a number");
    return it->get<double>();
}

template <class Enum>
Enum enum_member(const json& doc, const char* name, Enum fallback, std::optional<Enum> (*from_string)(std::string_view),
                 const char* choices, const std::string& where) {
    auto it = doc.find(name);
    if (it == doc.end()) return fallback;
    if (!it->is_string()) fail(where, std::string("\"") + name + "\" must be one of " + choices);
    auto value = from_string(it->get<std::string>());
    if (!value) fail(where, std::string("\"") + name + "\" is \"" + it->get<std::string>() + "\", expected " + choices);
    return *value;
}

// One preset from its JSON object; `where` names it in messages.
Preset preset_from(const json& doc, const std::string& where) {
    if (!doc.is_object()) fail(where, "a preset must be a JSON object");
    for (const auto& [key, value] : doc.items())
        if (!known_members().count(key)) fail(where, "unknown member \"" + key + "\"");

    Preset p;
    auto name = doc.find("name");
    if (name == doc.end()) fail(where, "missing \"name\"");
    if (!name->is_string()) fail(where, "\"name\" must be a string");
    p.name = name->get<std::string>();
    const std::string named = where + " (\"" + p.name + "\")";

    p.opacity_min = number_member(doc, "opacity_min", p.opacity_min, named);
    p.opacity_max = number_member(doc, "opacity_max", p.opacity_max, named);
    p.period_s = number_member(doc, "period_s", p.period_s, named);
    p.waveform = enum_member(doc, "waveform", p.waveform, waveform_from_string, "\"sine\" or \"triangle\"", named);
    p.module_px = number_member(doc, "module_px", p.module_px, named);
    if (auto pal = doc.find("palette"); pal != doc.end()) {
        if (!pal->is_array()) fail(named, "\"palette\" must be an array of \"#rrggbb\" strings");
        for (const auto& c : *pal) {
            if (!c.is_string()) fail(named, "\"palette\" must be an array of \"#rrggbb\" strings");
            p.palette.push_back(c.get<std::string>());
        }
    }
    p.blur = number_member(doc, "blur", p.blur, named);
    p.region = enum_member(doc, "region", p.region, region_from_string, "\"full\" or \"focus\"", named);
    p.focus_radius_modules = number_member(doc, "focus_radius_modules", p.focus_radius_modules, named);
    p.activation =
        enum_member(doc, "activation", p.activation, activation_from_string, "\"always\" or \"on_demand\"", named);
    p.fade_s = number_member(doc, "fade_s", p.fade_s, named);

    if (auto problem = describe_invalid(p); !problem.empty()) fail(named, problem);
    return p;
}

nlohmann::ordered_json preset_object(const Preset& p) {
    if (auto problem = describe_invalid(p); !problem.empty())
        throw std::invalid_argument("cannot write an invalid preset: " + problem);
    // ordered_json keeps the members in the order a reader expects.
    nlohmann::ordered_json o;
    o["name"] = p.name;
    o["opacity_min"] = p.opacity_min;
    o["opacity_max"] = p.opacity_max;
    o["period_s"] = p.period_s;
    o["waveform"] = to_string(p.waveform);
    o["module_px"] = p.module_px;
    o["palette"] = p.palette;
    o["blur"] = p.blur;
    o["region"] = to_string(p.region);
    o["focus_radius_modules"] = p.focus_radius_modules;
    o["activation"] = to_string(p.activation);
    o["fade_s"] = p.fade_s;
    return o;
}

json parse_text(const std::string& text, const std::string& source) {
    if (text.size() > kMaxPresetFileBytes)
        fail(source, "file is " + std::to_string(text.size()) + " bytes, more than the limit of " +
                         std::to_string(kMaxPresetFileBytes));
    json doc = json::parse(text, nullptr, false);
    if (doc.is_discarded()) fail(source, "not valid JSON");
    return doc;
}

}  // namespace

const char* to_string(Waveform w) { return w == Waveform::sine ? "sine" : "triangle"; }
const char* to_string(Region r) { return r == Region::full ? "full" : "focus"; }
const char* to_string(Activation a) { return a == Activation::always ? "always" : "on_demand"; }

std::optional<Waveform> waveform_from_string(std::string_view name) {
    if (name == "sine") return Waveform::sine;
    if (name == "triangle") return Waveform::triangle;
    return std::nullopt;
}

std::optional<Region> region_from_string(std::string_view name) {
    if (name == "full") return Region::full;
    if (name == "focus") return Region::focus;
    return std::nullopt;
}

std::optional<Activation> activation_from_string(std::string_view name) {
    if (name == "always") return Activation::always;
    if (name == "on_demand") return Activation::on_demand;
    return std::nullopt;
}

std::vector<Preset> built_in_presets() {
    auto make = [](std::string name, double lo, double hi, double period, Activation activation) {
        Preset p;
        p.name = std::move(name);
        p.opacity_min = lo;
        p.opacity_max = hi;
        p.period_s = period;
        p.activation = activation;
        return p;
    };
    std::vector<Preset> out;
    out.push_back(make("subtle", 0.08, 0.25, 1.5, Activation::on_demand));
    out.push_back(make("balanced", 0.1, 0.4, 1.5, Activation::on_demand));
    out.push_back(make("visible", 0.3, 0.5, 2.0, Activation::always));
    out.push_back(make("static", 0.3, 0.3, 0.0, Activation::always));
    Preset kiosk = make("kiosk", 0.15, 0.4, 1.5, Activation::always);
    kiosk.module_px = 40.0;  // read from across a room
    out.push_back(kiosk);
    // A pulse of a few grey levels, found by demodulating it over the
    // phone's frames (shared/detect/pulse_search.hpp), not in any one frame.
    out.push_back(make("invisible", 0.01, 0.04, 1.5, Activation::on_demand));
    return out;
}

const Preset* find_preset(const std::vector<Preset>& presets, std::string_view name) {
    for (const auto& p : presets)
        if (p.name == name) return &p;
    return nullptr;
}

std::string describe_invalid(const Preset& p) {
    if (p.name.empty()) return "\"name\" must not be empty";
    if (p.name.size() > kMaxPresetNameBytes)
        return "\"name\" must be at most " + std::to_string(kMaxPresetNameBytes) + " bytes long";
    // The two error handlers write different text only when there is an invalid byte to replace or drop.
    if (json(p.name).dump(-1, ' ', false, json::error_handler_t::replace) !=
        json(p.name).dump(-1, ' ', false, json::error_handler_t::ignore))
        return "\"name\" is not valid UTF-8";
    for (auto [member, value] : {std::pair{"opacity_min", p.opacity_min}, std::pair{"opacity_max", p.opacity_max},
                                 std::pair{"blur", p.blur}})
        if (auto problem = outside(member, value, 0.0, 1.0); !problem.empty()) return problem;
    if (p.opacity_min > p.opacity_max)
        return "\"opacity_min\" " + number_text(p.opacity_min) + " is above \"opacity_max\" " +
               number_text(p.opacity_max);
    if (p.period_s != 0.0) {
        if (auto problem = outside("period_s", p.period_s, kMinPeriodS, kMaxPeriodS); !problem.empty())
            return problem + " (0 for a static field)";
    }
    if (auto problem = outside("module_px", p.module_px, kMinModulePx, kMaxModulePx); !problem.empty())
        return problem;
    if (!p.palette.empty() && (p.palette.size() < 2 || p.palette.size() > 10))
        return "\"palette\" must be empty (the field's own) or have 2 to 10 colours, not " +
               std::to_string(p.palette.size());
    for (const auto& c : p.palette)
        if (!is_hex_colour(c)) return "\"palette\" entry '" + c + "' is not a #rrggbb colour";
    if (auto problem = outside("focus_radius_modules", p.focus_radius_modules, 1.0, kMaxFocusRadiusModules);
        !problem.empty())
        return problem;
    if (auto problem = outside("fade_s", p.fade_s, 0.0, kMaxFadeS); !problem.empty()) return problem;
    return {};
}

std::string preset_to_json(const Preset& preset) {
    return preset_object(preset).dump(2) + "\n";
}

Preset parse_preset(const std::string& text, const std::string& source) {
    return preset_from(parse_text(text, source), source);
}

std::vector<Preset> parse_presets(const std::string& text, const std::string& source) {
    json doc = parse_text(text, source);
    if (!doc.is_array()) fail(source, "the top level must be a JSON array of presets");
    if (doc.size() > kMaxPresets)
        fail(source, std::to_string(doc.size()) + " presets, more than the limit of " + std::to_string(kMaxPresets));
    std::vector<Preset> out;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        Preset p = preset_from(doc[i], source + ": preset " + std::to_string(i));
        if (find_preset(out, p.name))
            fail(source + ": preset " + std::to_string(i), "name \"" + p.name + "\" is used twice");
        out.push_back(std::move(p));
    }
    return out;
}

std::string presets_to_json(const std::vector<Preset>& presets) {
    std::set<std::string> names;
    for (const auto& p : presets)
        if (!names.insert(p.name).second)
            throw std::invalid_argument("cannot write presets: the name \"" + p.name + "\" is used twice");
    // One preset per line: a file a person edits and a diff reads.
    std::string out = "[\n";
    for (std::size_t i = 0; i < presets.size(); ++i) {
        out += "  " + preset_object(presets[i]).dump();
        out += i + 1 < presets.size() ? ",\n" : "\n";
    }
    return out + "]\n";
}

std::vector<Preset> load_presets(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open the file");
    std::string text;
    // Read one byte past the limit so an oversized file is reported, not truncated.
    text.resize(kMaxPresetFileBytes + 1);
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (in.bad()) fail(path, "cannot read the file");
    return parse_presets(text, path);
}

void save_presets(const std::vector<Preset>& presets, const std::string& path) {
    std::string text = presets_to_json(presets);
    try {
        write_file_atomically(path, text);
    } catch (const FileWriteError& e) {
        throw PresetError(e.what());
    }
}

}  // namespace umf::overlay
