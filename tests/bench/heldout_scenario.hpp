// The held-out set of the detector benchmark: scenes made apart from the
// tuning set's (scenario.hpp) to measure the detector on data it was never
// tuned on. Other screens (a 13" 2560 x 1600 laptop with an OLED PenTile
// panel, a 27" 2560 x 1440 monitor, a 15.6" 1920 x 1080 laptop), other
// contents (sim/heldout_content.hpp), a wider phone camera (70-80 degrees),
// the second camera model (sim/phone_camera.hpp) at 30 fps, other distance
// ranges and other seeds. The screens appear turned at any angle in every
// category (roll spread over the whole circle).
//
// The rule: the held-out scenes are not looked at while changing the
// detector, and a change that helps one set and hurts the other is not taken.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shared/field/field.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/heldout_content.hpp"
#include "tests/sim/phone_camera.hpp"

namespace umf::bench {

enum class HeldoutCategory { general, rotation, perspective, near, far, motion, low_light, occlusion, moire };

inline constexpr std::array<HeldoutCategory, 9> kAllHeldoutCategories = {
    HeldoutCategory::general, HeldoutCategory::rotation,  HeldoutCategory::perspective,
    HeldoutCategory::near,    HeldoutCategory::far,       HeldoutCategory::motion,
    HeldoutCategory::low_light, HeldoutCategory::occlusion, HeldoutCategory::moire};

const char* to_string(HeldoutCategory category);
std::optional<HeldoutCategory> heldout_category_from_string(const std::string& name);

struct HeldoutScreen {
    const char* name;
    sim::ScreenGeometry geometry;
    sim::PixelLayout layout;
    double fill;  // of the black matrix, see sim::PixelStructure
};

const std::array<HeldoutScreen, 3>& heldout_screens();

// The field across the screen's width (module = width / field columns),
// centred vertically: on the 16:10 laptop bands above and below stay free.
sim::FieldPlacement heldout_placement(const HeldoutScreen& screen, const Field& field);

// Pixel quantities (blur, defocus, sharpening radius) are for a 1280 px wide
// image and scale with the resolution, as the same motion during the same
// exposure smears over more pixels of a finer sensor.
inline constexpr double kReferenceWidth = 1280;

struct HeldoutRecipe {
    int index = 0;
    int screen = 0;  // into heldout_screens()
    sim::HeldoutContent content = sim::HeldoutContent::spreadsheet;
    double hfov_deg = 75;
    sim::CameraPose pose;
    sim::PhoneShot shot;  // at kReferenceWidth
    std::optional<std::uint64_t> occluder_seed;
};

// `frames` frames at 30 fps: clips of 10 frames, each on one screen and
// content along one smooth curved hand path; cuts between clips.
std::vector<HeldoutRecipe> heldout_recipes(HeldoutCategory category, int frames, std::uint64_t seed);

// The pulsing video of one content: `frames` frames at 30 fps along one
// continuous hand path (no cuts) on screen `content % 3`, the general
// category's module sizes (10-30 px at the reference width) and tilts (to 40
// degrees), the screen at any roll; distance, tilt, roll and aim swing with
// periods of their own, so that they meet the pulse's phases in many
// combinations.
std::vector<HeldoutRecipe> heldout_pulsing_recipes(sim::HeldoutContent content, int frames, std::uint64_t seed);

// The field's opacity in frame `frame` of that video: the provider's default
// pulse (0.1 to 0.4 and back every 1.5 s) from a phase of the video's own.
double heldout_pulsing_opacity(sim::HeldoutContent content, int frame, std::uint64_t seed);
inline constexpr double kHeldoutFps = 30;  // every held-out video's frame rate
inline constexpr double kHeldoutPulseMin = 0.1, kHeldoutPulseMax = 0.4, kHeldoutPulsePeriodS = 1.5;

// Photographs the mixed screen (field or board blended in) at `resolution`.
// centre_on_screen is true only when the image centre is on the field, so
// that every method has a right answer.
Frame shoot_heldout(const HeldoutRecipe& recipe, const cv::Mat& mixed_screen, cv::Size resolution,
                    const sim::FieldPlacement& placement, cv::Size field_modules);

}  // namespace umf::bench
