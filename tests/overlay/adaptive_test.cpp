// The overlay following its requesters: lower while locks come easily, up at
// once when one struggles, back to the preset when nobody looks; the focus
// region grows the same way, within bounds.
#include <gtest/gtest.h>

#include "shared/overlay/adaptive.hpp"
#include "shared/overlay/pulse.hpp"

namespace {

using namespace umf::overlay;

Preset static_preset() {
    Preset p;
    p.name = "t";
    p.opacity_min = 0.1;
    p.opacity_max = 0.5;
    p.period_s = 0.0;  // static at opacity_max: the level alone moves it
    p.focus_radius_modules = 8.0;
    return p;
}

TEST(AdaptiveOverlay, EasyLocksLowerTheFieldSlowlyDownToThePresetsFloor) {
    AdaptiveOverlay a(static_preset());
    EXPECT_DOUBLE_EQ(a.opacity(0.0), 0.5);
    for (int i = 0; i <= 40; ++i) a.aim(i * 0.5, 0.97);  // 20 s of easy locks, 2 aims a second
    EXPECT_NEAR(a.level(20.0), 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(a.opacity(20.0), 0.1) << "never below opacity_min";
    AdaptiveOverlay b(static_preset());
    for (int i = 0; i <= 4; ++i) b.aim(i * 0.5, 0.97);
    EXPECT_NEAR(b.level(2.0), 0.9, 1e-9) << "5 % of the range a second";
}

TEST(AdaptiveOverlay, StrugglingRaisesAtOnceAndGrowsTheFocus) {
    AdaptiveOverlay a(static_preset());
    for (int i = 0; i <= 20; ++i) a.aim(i * 0.5, 0.97);
    const double low = a.level(10.0);
    a.aim(10.2, 0.5);
    EXPECT_NEAR(a.level(10.2), low - 0.05 * 0.2 + 0.25, 1e-9);
    EXPECT_DOUBLE_EQ(a.focus_radius_modules(), 12.0);
    for (int i = 0; i < 10; ++i) a.seeking(10.5 + i * 0.1);
    EXPECT_DOUBLE_EQ(a.level(11.5), 1.0);
    EXPECT_DOUBLE_EQ(a.focus_radius_modules(), 32.0) << "at most four times the preset's radius";
}

TEST(AdaptiveOverlay, NobodyLookingResetsToThePreset) {
    AdaptiveOverlay a(static_preset());
    for (int i = 0; i <= 20; ++i) a.aim(i * 0.5, 0.97);
    a.seeking(10.1);
    a.seeking(10.2);
    EXPECT_DOUBLE_EQ(a.level(20.0), 1.0);
    EXPECT_DOUBLE_EQ(a.focus_radius_modules(), 8.0);
}

TEST(AdaptiveOverlay, APulseKeepsItsShapeScaledAboveTheFloor) {
    Preset p = static_preset();
    p.period_s = 2.0;
    AdaptiveOverlay a(p);
    EXPECT_DOUBLE_EQ(a.opacity(0.0), 0.1);  // the pulse starts at its minimum
    EXPECT_DOUBLE_EQ(a.opacity(1.0), opacity_at(p, 1.0));
    for (int i = 0; i <= 20; ++i) a.aim(i * 0.5, 0.97);  // level 0.5 at t = 10
    EXPECT_NEAR(a.opacity(11.0), 0.1 + (0.5 - 0.1) * 0.5, 1e-9);
}

}  // namespace
