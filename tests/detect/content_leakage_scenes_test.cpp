// The content's leakage taken out of the slope (content_leakage.hpp) on the
// pulsing benchmark's own frames: the tuning set's spreadsheet
// (tests/bench/scenario.hpp) while the hand brings the phone from 370 to
// 210 mm and from a pitch of 59 to 37 degrees, the field pulsing between
// 0.01 and 0.04. The frames are laid onto the newest by their true
// homographies, so that what stays of the content is not a registration's
// error. Photographs: left out of the sanitizer build, which runs
// content_leakage_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "shared/detect/detector.hpp"
#include "shared/detect/frame_registration.hpp"
#include "shared/detect/pulse_demodulator.hpp"
#include "shared/detect/pulse_search.hpp"
#include "tests/bench/heldout_scenario.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/detect/photo.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"

namespace content_leakage_scenes {

using namespace umf;

Eigen::Matrix3d screen_to_image_of(const bench::Scene& scene, const sim::CameraPose& pose) {
    const cv::Matx33d m = sim::screen_to_image(scene.screen, sim::CameraModel{{640, 480}, scene.hfov_deg}, pose);
    Eigen::Matrix3d e;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) e(r, c) = m(r, c);
    return e;
}

TEST(ContentLeakageScenes, TheSpreadsheetsFieldIsFoundInTheSlopeWithoutItsLeakage) {
    constexpr double kLow = 0.01, kHigh = 0.04;
    constexpr int kFirst = 20, kLast = 43;
    const Field field = test::shipped_field("b4-64x36.json");
    const Detector detector(field);
    const bench::Scene scene;
    const sim::FieldPlacement placement{{0, 0}, scene.module_px};
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::spreadsheet, scene.screen.pixels, 7);
    const auto recipes = bench::pulsing_recipes(scene, sim::ScreenKind::spreadsheet, kLast + 1, 1);
    const bench::FrameRecipe& newest = recipes.at(kLast);
    const Eigen::Matrix3d newest_from_screen = screen_to_image_of(scene, newest.pose);
    std::vector<bench::Frame> frames;
    std::vector<double> opacities;
    for (int i = kFirst; i <= kLast; ++i) {
        const bench::FrameRecipe& r = recipes.at(static_cast<std::size_t>(i));
        // The benchmark's faint pulse: the default pulse's phase, scaled.
        const double a = kLow + (kHigh - kLow) * (bench::pulsing_opacity(r.index) - bench::kHeldoutPulseMin) /
                                    (bench::kHeldoutPulseMax - bench::kHeldoutPulseMin);
        frames.push_back(bench::shoot(scene, r, sim::mix_field(screen, field, placement, a), cv::Size(640, 480)));
        opacities.push_back(a);
    }
    const GreyView newest_view = test::grey_view(frames.back().grey);
    PulseDemodulator demodulator;
    std::vector<std::uint8_t> warped;
    for (int i = kFirst; i <= kLast; ++i) {
        const auto k = static_cast<std::size_t>(i - kFirst);
        const Eigen::Matrix3d to_newest =
            newest_from_screen * screen_to_image_of(scene, recipes.at(static_cast<std::size_t>(i)).pose).inverse();
        const GreyView frame = test::grey_view(frames[k].grey);
        demodulator.add(i == kLast ? newest_view : warp_frame(frame, to_newest, newest_view, warped), opacities[k]);
    }
    const PulseSearchOptions options;
    const Eigen::Vector2d aim(320, 240);
    auto found_in = [&](const GreyView& image, const std::vector<SearchPlan>& plans) {
        const auto size = static_cast<std::size_t>(image.width) * image.height;
        std::vector<std::uint8_t> inverse(image.data, image.data + size);
        for (auto& v : inverse) v = static_cast<std::uint8_t>(255 - v);
        Detection d = detector.detect(image, aim, nullptr, plans);
        const GreyView inverted{inverse.data(), image.width, image.height, image.width};
        if (!d.found) d = detector.detect(inverted, aim, nullptr, plans);
        return d;
    };
    const Detection plain =
        found_in(demodulator.field_image(PulseDemodulator::SlopeScale::spread), options.content_free_plans);
    EXPECT_FALSE(plain.found) << "the content's edges fill the plain slope";
    const int tile = static_cast<int>(std::lround(options.content_free_tile * 640));
    const Detection free = found_in(demodulator.content_free_field_image(tile), options.content_free_plans);
    ASSERT_TRUE(free.found) << free.failure;
    const cv::Point2d at = sim::field_to_screen(placement, {free.aim_field.x(), free.aim_field.y()});
    EXPECT_LT(cv::norm(at - frames.back().centre_screen_px) / placement.module_px, 0.5);
}

}  // namespace content_leakage_scenes
