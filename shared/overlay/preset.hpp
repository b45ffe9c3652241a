// Overlay presets: how the provider mixes the field into the screen. A preset
// file is a JSON array of presets; the provider reads the user's own from its
// configuration directory, next to the built-ins.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace umf::overlay {

// The pulse between opacity_min and opacity_max.
enum class Waveform { sine, triangle };
// Where the field is shown: everywhere, or only within focus_radius_modules
// of the last aim point.
enum class Region { full, focus };
// When the field is shown: always, or only while a requester seeks or aims
// (and for fade_s after that).
enum class Activation { always, on_demand };

const char* to_string(Waveform w);
const char* to_string(Region r);
const char* to_string(Activation a);
std::optional<Waveform> waveform_from_string(std::string_view name);
std::optional<Region> region_from_string(std::string_view name);
std::optional<Activation> activation_from_string(std::string_view name);

// Ranges a preset must keep. A pulse faster than 2 Hz would flash: WCAG 2.3.1
// draws the line at three flashes a second, and a faint field is no reason to
// go near it.
inline constexpr double kMinPeriodS = 0.5;
inline constexpr double kMaxPeriodS = 60.0;
inline constexpr double kMinModulePx = 4.0;  // below this no camera resolves a module
inline constexpr double kMaxModulePx = 256.0;
inline constexpr double kMaxFocusRadiusModules = 1000.0;
inline constexpr double kMaxFadeS = 600.0;
inline constexpr std::size_t kMaxPresetNameBytes = 64;
inline constexpr std::size_t kMaxPresetFileBytes = 1u << 20;
inline constexpr std::size_t kMaxPresets = 256;

struct Preset {
    std::string name;
    double opacity_min = 0.1;  // 0..1, at most opacity_max
    double opacity_max = 0.4;
    double period_s = 1.5;  // 0: static at opacity_max; otherwise kMinPeriodS..kMaxPeriodS
    Waveform waveform = Waveform::sine;
    double module_px = 30.0;             // module side at 96 dpi; the provider scales it by the screen's dpi / 96
    std::vector<std::string> palette;    // "#rrggbb" per field colour; empty: the field's own
    double blur = 0.0;                   // 0..1: how much the background under the field is blurred
    Region region = Region::full;
    double focus_radius_modules = 8.0;   // used with Region::focus
    Activation activation = Activation::on_demand;
    double fade_s = 3.0;                 // on_demand: fade-out after the requester stops (see pulse.hpp)

    bool operator==(const Preset&) const = default;
};

// A preset file that cannot be read or holds an invalid preset. The message
// names the source, the preset and the member at fault.
class PresetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// subtle, balanced, visible, static, kiosk, invisible; all valid.
std::vector<Preset> built_in_presets();
// The preset called `name`, or nullptr.
const Preset* find_preset(const std::vector<Preset>& presets, std::string_view name);

// Empty when the preset keeps every range above; otherwise the first problem,
// in words naming the member.
std::string describe_invalid(const Preset& preset);

// One preset as a JSON object, every member written.
std::string preset_to_json(const Preset& preset);
// Members other than "name" may be left out and take the defaults above;
// unknown members are refused, since a misspelt one in a hand-edited file
// would otherwise be silently ignored.
Preset parse_preset(const std::string& json_text, const std::string& source_name = "preset");

// A preset file: a JSON array of presets with distinct names.
std::vector<Preset> parse_presets(const std::string& json_text, const std::string& source_name = "presets");
std::string presets_to_json(const std::vector<Preset>& presets);
std::vector<Preset> load_presets(const std::string& path);
// Writes through a temporary file and a rename.
void save_presets(const std::vector<Preset>& presets, const std::string& path);

}  // namespace umf::overlay
