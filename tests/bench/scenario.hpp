// What the detector benchmark photographs: the thesis's test categories as
// recipes of frames (camera pose, screen content, degradations, occluder),
// and the pulsing-opacity video. A recipe depends only on its category, the
// frame index and the seed, never on the opacity, the camera resolution or
// the method under test, so every method and every opacity sees the very
// same scenes and differences in the results come from what was varied.
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tests/sim/camera.hpp"
#include "tests/sim/screen_content.hpp"
#include "tests/sim/screen_source.hpp"
#include "tests/sim/sensor_pipeline.hpp"
#include "tests/sim/sequence.hpp"

namespace umf::bench {

// The thesis's seven categories, then five that stress what a phone's
// video adds (strong smear, far views, very far views, low-quality
// compression, the screen's pixel grid), each with parameters of its own
// (the held-out set's are not copied here), `ruled`: the general
// category's views of a spreadsheet, whose rules run with the field's lines,
// and `sensor`: the general category's views through a third camera model,
// a sensor several times finer than the frame behind a colour filter array,
// demosaiced and scaled down (sim/sensor_pipeline.hpp).
enum class Category { near_far, horizontal, rotation, perspective, general, occlusion, low_light, smeared, distant,
                      compressed, tiny, pixel_grid, ruled, sensor };

inline constexpr std::array<Category, 14> kAllCategories = {
    Category::near_far, Category::horizontal, Category::rotation, Category::perspective, Category::general,
    Category::occlusion, Category::low_light, Category::smeared, Category::distant, Category::compressed,
    Category::tiny, Category::pixel_grid, Category::ruled, Category::sensor};

// Categories whose frames have no more than the everyday degradations, on the
// everyday screens.
bool is_plain(Category category);

const char* to_string(Category category);
std::optional<Category> category_from_string(const std::string& name);

// The physical setup shared by every frame: a 1920 x 1080 screen, 527 mm
// wide (a 24" monitor), the field's 30 px modules covering all of it, and a
// phone camera with a 65 degree horizontal field of view.
struct Scene {
    sim::ScreenGeometry screen;
    double module_px = 30;
    double hfov_deg = 65;
    // 200..600 mm puts a 30 px module at about 7..21 image px at 640 x 480
    // and 21..62 px at 1920 x 1080.
    sim::MotionRange range{350, 200, 600, 60};
};

struct FrameRecipe {
    int index = 0;
    sim::CameraPose pose;
    sim::Degradation degradation;
    sim::ScreenKind screen = sim::ScreenKind::blank;
    std::optional<std::uint64_t> occluder_seed;  // set: something is held in front of the screen
    // The motion blur is given for a 640 px wide frame and grows with the
    // frame's width, as the same hand motion does on a finer sensor.
    bool smear_scales_with_width = false;
    // Set: photographed at the sensor's size (`degradation` in sensor
    // pixels, without its noise and JPEG) and developed into the frame.
    std::optional<sim::SensorPipeline> sensor;
};

// `frames` consecutive frames at 25 fps of the category's camera motion.
std::vector<FrameRecipe> category_recipes(const Scene& scene, Category category, int frames, std::uint64_t seed);

// The pulsing experiment: the provider pulses the opacity while the user
// swings the phone from looking up at the screen to looking steeply down on
// it (pitch about -20..+60 degrees) and moves it in and out (100..400 mm).
// One video per screen kind; frame i is shown at pulsing_opacity(i).
std::vector<FrameRecipe> pulsing_recipes(const Scene& scene, sim::ScreenKind kind, int frames, std::uint64_t seed);
double pulsing_opacity(int frame);

// A frame as the methods see it: the grey image and the truth about its centre.
struct Frame {
    cv::Mat grey;
    cv::Point2d centre_screen_px;
    bool centre_on_screen = false;
    double module_px_in_image = 0;
    double occluded_fraction = 0;
};

// Photographs `mixed_screen` (content with the field or the board blended
// in) as the recipe says, then draws the occluder if there is one. A
// screen shot many times is best made ready once (sim::ScreenSource, of the
// scene's screen geometry): the same frames at a fraction of the cost.
Frame shoot(const Scene& scene, const FrameRecipe& recipe, const cv::Mat& mixed_screen, cv::Size resolution);
Frame shoot(const Scene& scene, const FrameRecipe& recipe, const sim::ScreenSource& mixed_screen, cv::Size resolution);

// A hand or a mug between the phone and the screen, drawn into a photographed
// BGR frame: a shaded blob covering 15..35 % of the image from one of its
// borders, never over the image centre, its edge as soft as the defocus, with
// the frame's sensor noise. Returns the covered fraction. Depends only on
// the arguments.
double draw_occluder(cv::Mat& bgr, std::uint64_t seed, double edge_sigma_px, double noise_sigma);

}  // namespace umf::bench
