// The overlay manager following its requesters, on the offscreen platform:
// easy locks lower the field within the preset's range, a struggling
// requester raises it again at once, the windows carry the opacity the
// manager gives, a larger module in the preset or a new seed moves the field. With
// Region::focus and a blur, the screen under the circle (a grab function
// given by the test) is blurred and mixed into the circle by the window.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_PROVIDER_OVERLAY)

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QPainter>
#include <chrono>
#include <cmath>
#include <thread>

#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/screen/board_window.hpp"
#include "shared/overlay/background_blur.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/provider/qt_pump.hpp"

namespace {

using namespace umf::provider;
using umf::test::pump_until;

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
    for (OverlayWindow* w : manager.windows()) {
        // The pixels carry the preset's most, the window's opacity the pulse's share of it.
        EXPECT_NEAR(w->pixel_opacity(), 0.5, 1e-9);
        EXPECT_NEAR(w->opacity() * w->pixel_opacity(), lowered, 1.0 / 255 + 1e-6);
    }

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

// A screen's new seed (`pair --rotate --field` while it runs): every window
// shows the new field, and the service hears of it as of a change of screens.
TEST(OverlayManager, AnotherFieldSourceIsShownAndRelayed) {
    umf::test::ensure_gui_application();
    OverlayManager manager(steady_preset(), nullptr, FieldSource(0x1234, {}));
    ASSERT_TRUE(manager.layout());
    int changes = 0;
    manager.on_screens_changed([&] { ++changes; });
    const std::string before = manager.layout()->field.id;

    manager.set_fields(FieldSource(0x5678, {}));
    EXPECT_EQ(changes, 1);
    ASSERT_TRUE(manager.layout());
    EXPECT_NE(manager.layout()->field.id, before);
    EXPECT_NE(manager.layout()->field.id.find("5678"), std::string::npos) << manager.layout()->field.id;
    EXPECT_EQ(manager.windows()[0]->screen_field().field.id, manager.layout()->field.id);
}

// Black and white squares of 3 root pixels: edges far finer than a module.
QImage checkerboard(const QRect& root_rect) {
    QImage image(root_rect.size(), QImage::Format_RGB32);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const bool white = (((root_rect.x() + x) / 3) + ((root_rect.y() + y) / 3)) % 2 == 0;
            image.setPixel(x, y, white ? qRgb(255, 255, 255) : qRgb(0, 0, 0));
        }
    return image;
}

QImage render(OverlayWindow& window) {
    QImage image(window.size(), QImage::Format_ARGB32_Premultiplied);
    image.fill(Qt::transparent);
    QPainter painter(&image);
    window.paint_to(painter, QRegion(image.rect()));
    return image;
}

struct GrabLog {
    std::vector<QRect> asked;
    std::vector<QImage> given;
};

TEST(OverlayManager, FocusWithBlurMixesTheBlurredScreenIntoTheCircle) {
    umf::test::ensure_gui_application();
    umf::overlay::Preset preset = steady_preset();
    preset.region = umf::overlay::Region::focus;
    preset.focus_radius_modules = 4;
    preset.blur = 1.0;
    OverlayManager manager(preset);
    ASSERT_EQ(manager.windows().size(), 1u);
    auto log = std::make_shared<GrabLog>();
    manager.set_grab_function([log](const QRect& rect) {
        log->asked.push_back(rect);
        log->given.push_back(checkerboard(rect));
        return log->given.back();
    });
    OverlayWindow& window = *manager.windows()[0];
    const OverlayScreen screen = manager.screens()[0];
    ASSERT_EQ(window.devicePixelRatio(), 1.0) << "the offscreen platform's";
    const double module = window.screen_field().placement.module_px;
    const double radius = 4 * module;
    ASSERT_GE(screen.root_rect.width(), 6 * radius) << "the screen is too small for the test";
    const QImage layer = field_layer(window.screen_field(), preset.palette);

    // The circle well inside the left part of the screen; two aims close by.
    const QPointF centre(1.3 * radius, screen.root_rect.height() / 2.0);
    manager.set_focus(screen.index, centre);
    manager.set_focus(screen.index, centre + QPointF(module / 2, module / 3));
    ASSERT_TRUE(pump_until([&] { return !log->asked.empty() && !manager.grab_pending(); }, 3000));
    const QPointF aimed = centre + QPointF(module / 2, module / 3);
    manager.set_focus(screen.index, aimed + QPointF(-module / 2, 0));  // and another, still near
    pump_until([] { return false; }, 2 * OverlayManager::kMinGrabIntervalMs);
    ASSERT_EQ(log->asked.size(), 1u) << "nearby aims grabbed again";
    const QPointF now = aimed + QPointF(-module / 2, 0);
    // The grab held the circle with room around it, from the screen's root.
    const QRect asked = log->asked[0];
    EXPECT_TRUE(asked.contains(QRectF(now.x() - radius, now.y() - radius, 2 * radius, 2 * radius).toAlignedRect().translated(screen.root_rect.topLeft())));
    EXPECT_TRUE(window.painted_pulse());
    EXPECT_EQ(window.opacity(), 1.0) << "the window's opacity stays 1 with the painted pulse";
    EXPECT_FALSE(window.backdrop_rect().isEmpty());

    // The reference: the same grab blurred as the preset says.
    QImage blurred = log->given[0].copy();
    ASSERT_TRUE(umf::overlay::blur_background({blurred.bits(), blurred.width(), blurred.height(), blurred.bytesPerLine(), 4, true},
                                              {0, 0, blurred.width(), blurred.height()}, 1.0, module));
    auto check_mix = [&](double a) {
        const QImage shown = render(window);
        int worst = 0, probed = 0, off_grey = 0;
        const QPointF c = now;
        for (int y = static_cast<int>(c.y() - 0.6 * radius); y <= c.y() + 0.6 * radius; y += 5)
            for (int x = static_cast<int>(c.x() - 0.6 * radius); x <= c.x() + 0.6 * radius; x += 5) {
                if (std::hypot(x + 0.5 - c.x(), y + 0.5 - c.y()) > 0.6 * radius) continue;
                const QRgb field = layer.pixel(x, y);
                if (qAlpha(field) != 255) continue;
                const QRgb under = blurred.pixel(x + screen.root_rect.x() - asked.x(), y + screen.root_rect.y() - asked.y());
                off_grey = std::max(off_grey, std::abs(qRed(under) - 128));
                const QRgb got = shown.pixel(x, y);
                EXPECT_EQ(qAlpha(got), 255) << "at " << x << "," << y;
                const int pairs[3][3] = {{qRed(got), qRed(under), qRed(field)},
                                         {qGreen(got), qGreen(under), qGreen(field)},
                                         {qBlue(got), qBlue(under), qBlue(field)}};
                for (const auto& [g, u, f] : pairs)
                    worst = std::max(worst, std::abs(g - static_cast<int>(std::lround((1 - a) * u + a * f))));
                ++probed;
            }
        EXPECT_GE(probed, 50);
        EXPECT_LE(worst, 2) << "at opacity " << a;
        // It is blurred: the checkerboard's squares are gone to a grey.
        EXPECT_LE(off_grey, 12);
        // Outside the circle nothing.
        int outside = 0;
        for (int y = 0; y < shown.height(); y += 7)
            for (int x = 0; x < shown.width(); x += 7)
                if (std::hypot(x + 0.5 - c.x(), y + 0.5 - c.y()) > radius + 1) outside = std::max(outside, qAlpha(shown.pixel(x, y)));
        EXPECT_EQ(outside, 0);
    };
    EXPECT_NEAR(window.pulse_opacity(), manager.opacity(), 1e-9);
    EXPECT_NEAR(window.pulse_opacity(), 0.5, 1.0 / 255);
    check_mix(window.pulse_opacity());
    // The pulse is painted: another opacity, another mix, the window still at 1.
    window.set_opacity(0.25);
    EXPECT_EQ(window.opacity(), 1.0);
    check_mix(0.25);

    // A far move: grabbed again, there.
    const QPointF far = now + QPointF(2.5 * radius, 0);
    manager.set_focus(screen.index, far);
    ASSERT_TRUE(pump_until([&] { return log->asked.size() == 2 && !manager.grab_pending(); }, 3000))
        << log->asked.size() << " grabs";
    EXPECT_TRUE(log->asked[1].contains(QRectF(far.x() - radius, far.y() - radius, 2 * radius, 2 * radius).toAlignedRect().translated(screen.root_rect.topLeft())));
    EXPECT_TRUE(window.backdrop_rect().contains(QRectF(far.x() - radius, far.y() - radius, 2 * radius, 2 * radius).toAlignedRect()));

    // Another strength blurs the same grab again; no new grab.
    preset.blur = 0.5;
    manager.set_preset(preset);
    pump_until([] { return false; }, 100);
    EXPECT_EQ(log->asked.size(), 2u);
    EXPECT_TRUE(window.painted_pulse());

    // Blur 0, live: the compositor's pulse again, no backdrop, no grab.
    preset.blur = 0;
    manager.set_preset(preset);
    EXPECT_FALSE(window.painted_pulse());
    EXPECT_TRUE(window.backdrop_rect().isEmpty());
    EXPECT_NEAR(window.opacity() * window.pixel_opacity(), manager.opacity(), 1.0 / 255 + 1e-6);
    manager.set_focus(screen.index, centre);
    pump_until([] { return false; }, 2 * OverlayManager::kMinGrabIntervalMs);
    EXPECT_EQ(log->asked.size(), 2u) << "grabbed without a blur";
}

TEST(OverlayManager, AimsDuringAGrabAreCoalesced) {
    umf::test::ensure_gui_application();
    umf::overlay::Preset preset = steady_preset();
    preset.region = umf::overlay::Region::focus;
    preset.focus_radius_modules = 3;
    preset.blur = 1.0;
    OverlayManager manager(preset);
    auto asked = std::make_shared<std::vector<QRect>>();
    manager.set_grab_function([asked](const QRect& rect) {
        asked->push_back(rect);
        return checkerboard(rect);
    });
    const OverlayScreen screen = manager.screens()[0];
    const double radius = 3 * screen.field.placement.module_px;
    // Far apart, one after the other before the grab is made: one grab, at the last.
    const QPointF a(1.2 * radius, 1.2 * radius), b(screen.root_rect.width() - 1.2 * radius, 1.2 * radius);
    manager.set_focus(screen.index, a);
    manager.set_focus(screen.index, b);
    ASSERT_TRUE(pump_until([&] { return !asked->empty() && !manager.grab_pending(); }, 3000));
    pump_until([] { return false; }, 100);
    ASSERT_EQ(asked->size(), 1u);
    EXPECT_TRUE(asked->front().contains(b.toPoint() + screen.root_rect.topLeft()));
    EXPECT_FALSE(asked->front().contains(a.toPoint() + screen.root_rect.topLeft()));

    // Region full with a blur: not on a live desktop; no grab, the compositor's pulse.
    preset.region = umf::overlay::Region::full;
    manager.set_preset(preset);
    manager.set_focus(screen.index, a);
    pump_until([] { return false; }, 2 * OverlayManager::kMinGrabIntervalMs);
    EXPECT_EQ(asked->size(), 1u);
    EXPECT_FALSE(manager.windows()[0]->painted_pulse());
}

// How many pixels of the rendered window are not transparent.
int drawn_pixels(OverlayWindow& window) {
    const QImage image = render(window);
    int n = 0;
    for (int y = 0; y < image.height(); y += 4)
        for (int x = 0; x < image.width(); x += 4) n += qAlpha(image.pixel(x, y)) > 0;
    return n;
}

TEST(OverlayManager, FocusShowsTheWholeFieldUntilARequesterLocks) {
    umf::test::ensure_gui_application();
    umf::overlay::Preset preset = steady_preset();
    preset.region = umf::overlay::Region::focus;
    preset.focus_radius_modules = 3;
    OverlayManager manager(preset);
    ASSERT_EQ(manager.windows().size(), 1u);
    OverlayWindow& window = *manager.windows()[0];
    const int index = manager.screens()[0].index;
    const int everything = drawn_pixels(window);

    // Nobody locked: the whole field, or a phone could never lock.
    EXPECT_FALSE(manager.circles_shown());
    EXPECT_GT(everything, 1000);

    // A lock: only its circle.
    const QPointF at(200, 200);
    manager.set_focus(index, at);
    EXPECT_TRUE(manager.circles_shown());
    const int circle = drawn_pixels(window);
    EXPECT_GT(circle, 0);
    EXPECT_LT(circle, everything / 4);

    // Another requester seeks: the whole field again, for as long as it seeks.
    manager.report_seeking();
    EXPECT_FALSE(manager.circles_shown());
    EXPECT_EQ(drawn_pixels(window), everything);
    EXPECT_TRUE(pump_until([&] { return manager.circles_shown(); }, OverlayManager::kSeekingHoldMs + 1000))
        << "the circle did not come back after the seeking stopped";
    // Larger now: a struggling requester grows the focus region.
    const int grown = drawn_pixels(window);
    EXPECT_GT(grown, circle);
    EXPECT_LT(grown, everything / 2);

    // The locked one leaves: nobody is locked, the whole field.
    manager.set_focus(index, std::nullopt);
    EXPECT_FALSE(manager.circles_shown());
    EXPECT_EQ(drawn_pixels(window), everything);
}

TEST(OverlayManager, ThePointerRingHasAWindowOfItsOwnThatDoesNotPulse) {
    umf::test::ensure_gui_application();
    umf::overlay::Preset preset = steady_preset();
    preset.opacity_min = preset.opacity_max = 0.2;  // a faint field
    OverlayManager manager(preset);
    const int index = manager.screens()[0].index;
    EXPECT_TRUE(manager.aim_windows().empty());

    const QPointF at(300, 250);
    manager.set_aim_mark(index, at, "report.pdf");
    ASSERT_EQ(manager.aim_windows().size(), 1u);
    AimWindow& ring = *manager.aim_windows()[0];
    EXPECT_EQ(ring.title(), "report.pdf");
    EXPECT_EQ(ring.opacity(), 1.0) << "the ring must not fade with the field";
    // The ring's centre is on the point (the offscreen screen's origin is 0, 0).
    const QPointF centre = QPointF(ring.geometry().topLeft()) + ring.ring_centre();
    EXPECT_NEAR(centre.x(), at.x(), 1.0);
    EXPECT_NEAR(centre.y(), at.y(), 1.0);
    // Drawn at full strength: white on the ring, dark just outside it, clear
    // in the middle.
    QImage image(ring.size(), QImage::Format_ARGB32_Premultiplied);
    image.fill(Qt::transparent);
    {
        QPainter painter(&image);
        ring.paint_to(painter);
    }
    const QPoint c = ring.ring_centre().toPoint();
    const QRgb on_ring = image.pixel(c.x() + static_cast<int>(AimWindow::kRingRadius), c.y());
    EXPECT_GE(qAlpha(on_ring), 240);
    EXPECT_GT(qGray(on_ring), 200);
    EXPECT_EQ(qAlpha(image.pixel(c)), 0);
    // The title makes the window wider than the ring.
    EXPECT_GT(ring.width(), 2 * AimWindow::kRingRadius + 40);

    // A snapshot takes it away with the field, and brings it back.
    manager.hide_for_snapshot();
    EXPECT_TRUE(manager.aim_windows().empty());
    manager.show_after_snapshot();
    EXPECT_EQ(manager.aim_windows().size(), 1u);

    // Moved: the same window follows.
    manager.set_aim_mark(index, QPointF(900, 100), "");
    ASSERT_EQ(manager.aim_windows().size(), 1u);
    EXPECT_NEAR(manager.aim_windows()[0]->geometry().left() + manager.aim_windows()[0]->ring_centre().x(),
                900.0, 1.0);

    // Not moved for a while: it goes by itself.
    EXPECT_TRUE(pump_until([&] { return manager.aim_windows().empty(); }, OverlayManager::kAimMarkHoldMs + 1000));

    // Removed at once when told.
    manager.set_aim_mark(index, at, "x");
    EXPECT_EQ(manager.aim_windows().size(), 1u);
    manager.set_aim_mark(index, std::nullopt, {});
    EXPECT_TRUE(manager.aim_windows().empty());
}

}  // namespace

#endif
