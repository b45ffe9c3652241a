// Tests of the held-out set's recipes: reproducible, independent of the
// tuning set's seeds, screens turned steeply in every category, and the far
// category's modules at 6-9 image px at the reference width.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/bench/heldout_scenario.hpp"
#include "tests/sim/camera.hpp"

namespace {

using namespace umf;
using namespace umf::bench;

TEST(BenchHeldout, RecipesAreReproducible) {
    const auto a = heldout_recipes(HeldoutCategory::motion, 30, 1);
    const auto b = heldout_recipes(HeldoutCategory::motion, 30, 1);
    const auto c = heldout_recipes(HeldoutCategory::motion, 30, 2);
    ASSERT_EQ(a.size(), 30u);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].pose.roll_deg, b[i].pose.roll_deg);
        EXPECT_EQ(a[i].shot.blur.length_px, b[i].shot.blur.length_px);
        EXPECT_NE(a[i].pose.roll_deg, c[i].pose.roll_deg);
        EXPECT_GE(a[i].shot.blur.length_px, 4.0);
        EXPECT_LE(a[i].shot.blur.length_px, 14.0);
    }
}

TEST(BenchHeldout, EveryCategoryHasSteeplyTurnedScreens) {
    for (HeldoutCategory c : kAllHeldoutCategories) {
        int steep = 0;
        for (const auto& r : heldout_recipes(c, 120, 1)) {
            const double a = std::fmod(std::abs(r.pose.roll_deg), 180.0);
            steep += a >= 60 && a <= 120;
        }
        EXPECT_GT(steep, 10) << to_string(c);
    }
}

TEST(BenchHeldout, FarModulesAreSixToNinePixels) {
    for (const auto& r : heldout_recipes(HeldoutCategory::far, 40, 1)) {
        const auto& screen = heldout_screens()[static_cast<std::size_t>(r.screen)];
        const double module = screen.geometry.pixels.width / 64.0;
        const sim::CameraModel camera{{1280, 720}, r.hfov_deg};
        const cv::Matx33d h = sim::screen_to_image(screen.geometry, camera, r.pose);
        // Square-on the module at the aim point is the drawn size; tilt
        // (up to 25 degrees) shrinks its geometric mean a little.
        const double px = sim::screen_px_in_image_at(h, r.pose.aim_screen_px) * module;
        EXPECT_GE(px, 6 * 0.85) << r.index;
        EXPECT_LE(px, 9 * 1.02) << r.index;
    }
}

// The pulsing video is one continuous path: no cuts between frames, the
// general category's module sizes, and the pulse's whole range.
TEST(BenchHeldout, PulsingVideoIsOneContinuousPathThroughThePulse) {
    for (sim::HeldoutContent content : sim::kAllHeldoutContents) {
        const auto rs = heldout_pulsing_recipes(content, 90, 1);
        ASSERT_EQ(rs.size(), 90u);
        double lowest = 1, highest = 0, smallest = 1e9, largest = 0;
        for (std::size_t i = 0; i < rs.size(); ++i) {
            const auto& r = rs[i];
            EXPECT_EQ(r.screen, rs.front().screen);
            EXPECT_EQ(r.content, content);
            const auto& screen = heldout_screens()[static_cast<std::size_t>(r.screen)];
            const sim::CameraModel camera{{1280, 720}, r.hfov_deg};
            const cv::Matx33d h = sim::screen_to_image(screen.geometry, camera, r.pose);
            const double px = sim::screen_px_in_image_at(h, r.pose.aim_screen_px) * screen.geometry.pixels.width / 64.0;
            smallest = std::min(smallest, px);
            largest = std::max(largest, px);
            if (i > 0) {
                // A 30th of a second moves the aim by a few screen modules at most.
                const cv::Point2d step = r.pose.aim_screen_px - rs[i - 1].pose.aim_screen_px;
                EXPECT_LT(std::hypot(step.x, step.y), 0.02 * screen.geometry.pixels.width) << i;
                EXPECT_LT(std::abs(r.pose.roll_deg - rs[i - 1].pose.roll_deg), 3.0) << i;
            }
            const double op = heldout_pulsing_opacity(content, r.index, 1);
            EXPECT_GE(op, kHeldoutPulseMin - 1e-9);
            EXPECT_LE(op, kHeldoutPulseMax + 1e-9);
            lowest = std::min(lowest, op);
            highest = std::max(highest, op);
        }
        EXPECT_LT(lowest, 0.11) << sim::to_string(content);
        EXPECT_GT(highest, 0.39) << sim::to_string(content);
        EXPECT_GE(smallest, 10 * 0.7) << sim::to_string(content);
        EXPECT_LE(largest, 30 * 1.05) << sim::to_string(content);
    }
}

}  // namespace
