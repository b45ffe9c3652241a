// The overlay manager following its requesters, on the offscreen platform:
// easy locks lower the field within the preset's range, a struggling
// requester raises it again at once, the windows carry the opacity the
// manager gives, and a larger module in the preset moves the field.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_PROVIDER_OVERLAY)

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <chrono>
#include <thread>

#include "overlay/overlay_manager.hpp"
#include "provider/gui_test_app.hpp"

namespace {

using namespace umf::provider;

// Runs the event loop for `ms`, calling `each` every `step_ms`.
template <class Each>
void pump_for(int ms, int step_ms, Each each) {
    QElapsedTimer clock;
    clock.start();
    qint64 next = 0;
    while (clock.elapsed() < ms) {
        if (clock.elapsed() >= next) {
            each();
            next += step_ms;
        }
        QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
}

umf::overlay::Preset steady_preset() {
    umf::overlay::Preset preset;
    preset.name = "steady";
    preset.period_s = 0;  // static at the top of the range, so only adaptation moves it
    preset.opacity_min = 0.1;
    preset.opacity_max = 0.5;
    preset.activation = umf::overlay::Activation::always;
    return preset;
}

TEST(OverlayManager, EasyLocksLowerTheFieldAndStrugglingRaisesIt) {
    umf::test::ensure_gui_application();
    OverlayManager manager(steady_preset());
    ASSERT_FALSE(manager.windows().empty());
    EXPECT_NEAR(manager.opacity(), 0.5, 1e-9);

    // 3 s of confident aims at 5 a second: the field sinks slowly.
    pump_for(3000, 200, [&] { manager.report_aim(0.97); });
    const double lowered = manager.opacity();
    EXPECT_LT(lowered, 0.5 - 0.03) << "easy locks did not lower the field";
    EXPECT_GE(lowered, 0.1);
    for (OverlayWindow* w : manager.windows()) EXPECT_NEAR(w->opacity(), lowered, 1.0 / 255 + 1e-6);

    // Two reports of no lock: back up at once, by more than it sank.
    manager.report_seeking();
    manager.report_seeking();
    pump_for(100, 100, [] {});
    EXPECT_GT(manager.opacity(), lowered + 0.05);
    EXPECT_LE(manager.opacity(), 0.5 + 1e-9);

    // Weak aims count as struggling too, and never push past the preset.
    pump_for(1000, 100, [&] { manager.report_aim(0.3); });
    EXPECT_NEAR(manager.opacity(), 0.5, 1.0 / 255);
}

TEST(OverlayManager, APresetWithLargerModulesMovesTheField) {
    umf::test::ensure_gui_application();
    umf::overlay::Preset preset = steady_preset();
    OverlayManager manager(preset);
    ASSERT_TRUE(manager.layout());
    int changes = 0;
    manager.on_screens_changed([&] { ++changes; });
    const double before = manager.layout()->screens[0].field.placement.module_px;

    preset.module_px *= 2;
    manager.set_preset(preset);
    EXPECT_EQ(changes, 1);
    const double after = manager.layout()->screens[0].field.placement.module_px;
    EXPECT_GE(after, before);
    EXPECT_EQ(manager.windows()[0]->screen_field().placement, manager.layout()->screens[0].field.placement);

    // Another opacity alone relays nothing out.
    preset.opacity_max = 0.45;
    manager.set_preset(preset);
    EXPECT_EQ(changes, 1);
}

}  // namespace

#endif
