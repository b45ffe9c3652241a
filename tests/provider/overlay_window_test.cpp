// The overlay on a real, composited X desktop: Xvfb, openbox and xcompmgr,
// with a flat grey window below. The field shows mixed at the window's
// opacity, the pulse changes the screen without a repaint, clicks pass
// through, the overlay takes no focus, and the compositor is detected. In
// focus mode with a blur, over a fine checkerboard, the circle shows the
// field over the blurred pattern and the pattern is untouched around it.
//
// The Qt half runs in a child process (tests/provider/x11_child.hpp).
//
// UMF_PROVIDER_OVERLAY: defined once provider/field_overlay/ is built into the
// provider core; until then this file would not link.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_PROVIDER_OVERLAY)

#include <gtest/gtest.h>
#include <unistd.h>

#include <QElapsedTimer>
#include <QGuiApplication>
#include <QPainter>
#include <QRasterWindow>
#include <QScreen>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "provider/desktop/x11/compositor.hpp"
#include "provider/desktop/x11/overlay_window.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"
#include "provider/field_overlay/overlay_manager.hpp"
#include "provider/screen/board_window.hpp"
#include "provider/screen/screen_field.hpp"
#include "tests/provider/qt_pump.hpp"
#include "tests/provider/x11_child.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

// Last: Xlib's macros clash with Qt's headers.
#include <X11/Xlib.h>
#include <X11/extensions/shape.h>

namespace {

// The rectangles of a window's input shape on the X server; -1 when the
// server cannot say.
int input_rectangles(const std::string& display_name, unsigned long window) {
    Display* display = XOpenDisplay(display_name.c_str());
    if (!display) return -1;
    int count = -1, ordering = 0;
    XRectangle* rects = XShapeGetRectangles(display, window, ShapeInput, &count, &ordering);
    if (rects) XFree(rects);
    XCloseDisplay(display);
    return count;
}

namespace fs = std::filesystem;
using namespace umf::provider;
using namespace umf::test;

constexpr const char* kChildVariable = kX11ChildVariable;
constexpr int kGrey = 0x80;

// The window below the overlay: flat grey, counting the presses it gets.
class Backdrop : public QRasterWindow {
public:
    int presses = 0;

protected:
    void paintEvent(QPaintEvent*) override { QPainter(this).fillRect(QRect(QPoint(), size()), QColor(kGrey, kGrey, kGrey)); }
    void mousePressEvent(QMouseEvent*) override { ++presses; }
};

std::string active_window(const std::vector<std::string>& env) {
    const std::string line = run({"xprop", "-root", "_NET_ACTIVE_WINDOW"}, env);
    const auto hash = line.find('#');
    return hash == std::string::npos ? line : line.substr(hash + 2, line.find_first_of("\n,", hash) - hash - 2);
}

struct Probe {
    int x = 0, y = 0;
    QRgb colour = 0;  // the module's colour in the field layer
};

// Module centres spread over the field, each with a neighbour of another
// colour, so both colours are probed everywhere.
std::vector<Probe> probes(const ScreenField& field, const QImage& layer) {
    auto at = [&](int i, int j) {
        const auto p = umf::overlay::field_to_screen(field.placement, j + 0.5, i + 0.5);
        const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
        return Probe{x, y, layer.pixel(x, y)};
    };
    std::vector<Probe> out;
    for (int k = 1; k <= 3; ++k)
        for (int l = 1; l <= 3; ++l) {
            const int i = field.field.height * k / 4, j = field.field.width * l / 4;
            const Probe p = at(i, j);
            if (qAlpha(p.colour) != 255) continue;
            out.push_back(p);
            for (int d = 1; d < 4; ++d)
                if (const Probe q = at(i, j + d); q.colour != p.colour) {
                    out.push_back(q);
                    break;
                }
        }
    return out;
}

// How far the screen is from the field at `opacity` over the grey, the worst
// channel of any probe.
int mix_error(const X11Desktop& desktop, const std::vector<Probe>& ps, double opacity) {
    int worst = 0;
    for (const Probe& p : ps) {
        const Capture shot = desktop.capture({p.x, p.y, 1, 1});
        if (shot.pixels.empty()) return 255;
        const std::uint32_t got = shot.pixels[0];
        const int channels[3][2] = {{static_cast<int>((got >> 16) & 255), qRed(p.colour)},
                                    {static_cast<int>((got >> 8) & 255), qGreen(p.colour)},
                                    {static_cast<int>(got & 255), qBlue(p.colour)}};
        for (const auto& [screen, colour] : channels) {
            const int expected = static_cast<int>(std::lround((1 - opacity) * kGrey + opacity * colour));
            worst = std::max(worst, std::abs(screen - expected));
        }
    }
    return worst;
}

// Only in the child (see the top of the file): the overlay made through Qt.
TEST(OverlayWindowOnX, DISABLED_Child) {
    if (!std::getenv(kChildVariable)) GTEST_SKIP() << "run by OverlayWindow.MixesIntoACompositedDesktop";
    X11ChildApplication child;
    ASSERT_EQ(QGuiApplication::platformName(), "xcb");
    const std::string display = std::getenv("DISPLAY");
    const auto env = environment_with({});
    const X11Desktop desktop(display);
    QScreen* screen = QGuiApplication::primaryScreen();

    Backdrop backdrop;
    backdrop.setGeometry(screen->geometry());
    backdrop.show();
    backdrop.requestActivate();
    const std::string backdrop_id = [&] {
        char text[32];
        std::snprintf(text, sizeof text, "0x%llx", static_cast<unsigned long long>(backdrop.winId()));
        return std::string(text);
    }();
    ASSERT_TRUE(pump_until([&] { return active_window(env) == backdrop_id; }, 5000))
        << "the backdrop " << backdrop_id << " is not active: " << active_window(env);

    const ScreenField field = screen_field_for(1920, 1080);
    const std::vector<Probe> ps = probes(field, field_layer(field, {}));
    ASSERT_GE(ps.size(), 9u);
    ASSERT_TRUE(pump_until([&] { return mix_error(desktop, ps, 0.0) <= 1; }, 5000)) << "the backdrop is not shown";

    // (a) The field over the grey at the window's opacity. Its pixels carry
    // the preset's most (0.5 here), the window's opacity only the pulse's
    // share of it: at the top of the pulse the window is fully "opaque".
    auto owned = std::make_unique<OverlayWindow>(screen, field, std::vector<std::string>{});
    OverlayWindow& overlay = *owned;
    // (f) No click lands on it from its first frame: the input shape is
    // empty on the server before it is ever mapped.
    EXPECT_EQ(input_rectangles(display, overlay.winId()), 0);
    overlay.set_pixel_opacity(0.5);
    overlay.set_opacity(0.5);
    EXPECT_DOUBLE_EQ(overlay.opacity(), 1.0);
    overlay.show();
    int error = 255;
    EXPECT_TRUE(pump_until([&] { return (error = mix_error(desktop, ps, 0.5)) <= 3; }, 5000))
        << "worst channel off by " << error;
    EXPECT_EQ(input_rectangles(display, overlay.winId()), 0);

    // (d) Shown, it took no focus.
    pump_until([] { return false; }, 200);
    EXPECT_EQ(active_window(env), backdrop_id);

    // (b) The pulse reaches the screen without a repaint.
    const int paints = overlay.paint_count();
    EXPECT_GE(paints, 1);
    overlay.set_opacity(0.2);
    EXPECT_TRUE(pump_until([&] { return (error = mix_error(desktop, ps, 0.2)) <= 3; }, 5000))
        << "worst channel off by " << error;
    pump_until([] { return false; }, 200);
    EXPECT_EQ(overlay.paint_count(), paints);

    // (g) A compositor that ignores the window's opacity property still
    // shows a translucent field (at the pixels' 0.5), never an opaque one.
    char id[32];
    std::snprintf(id, sizeof id, "0x%llx", static_cast<unsigned long long>(overlay.winId()));
    run({"xprop", "-id", id, "-remove", "_NET_WM_WINDOW_OPACITY"}, env);
    EXPECT_TRUE(pump_until([&] { return (error = mix_error(desktop, ps, 0.5)) <= 3; }, 5000))
        << "without the opacity property, worst channel off by " << error;
    overlay.set_opacity(0.21);
    overlay.set_opacity(0.2);
    EXPECT_TRUE(pump_until([&] { return (error = mix_error(desktop, ps, 0.2)) <= 3; }, 5000))
        << "worst channel off by " << error;

    // (c) A click on the field reaches the window below.
    run({"xdotool", "mousemove", std::to_string(ps[0].x), std::to_string(ps[0].y), "click", "1"}, env);
    EXPECT_TRUE(pump_until([&] { return backdrop.presses > 0; }, 3000)) << "the click did not pass through";
    EXPECT_EQ(active_window(env), backdrop_id);

    // The focus mask: outside the circle the grey, inside the field.
    const double radius = 4 * field.placement.module_px;
    overlay.set_focus(QPointF(ps[0].x, ps[0].y), radius);
    std::vector<Probe> inside, outside;
    for (const Probe& p : ps)
        (std::hypot(p.x - ps[0].x, p.y - ps[0].y) < radius * 0.8 ? inside : outside).push_back(p);
    EXPECT_TRUE(pump_until(
        [&] { return mix_error(desktop, inside, 0.2) <= 3 && (outside.empty() || mix_error(desktop, outside, 0.0) <= 1); },
        3000))
        << "inside off by " << mix_error(desktop, inside, 0.2) << ", outside by " << mix_error(desktop, outside, 0.0);
    owned.reset();

    // The manager: an on-demand field comes up on a request and goes for a snapshot.
    umf::overlay::Preset preset;
    preset.period_s = 0;
    preset.opacity_max = 0.5;
    preset.activation = umf::overlay::Activation::on_demand;
    preset.fade_s = 600;
    OverlayManager manager(preset);
    const auto screens = manager.screens();
    ASSERT_EQ(screens.size(), 1u);
    EXPECT_EQ(screens[0].root_rect, QRect(0, 0, 1920, 1080));
    EXPECT_FALSE(screens[0].name.isEmpty());
    EXPECT_EQ(screens[0].field.placement, field.placement);
    EXPECT_TRUE(pump_until([&] { return mix_error(desktop, ps, 0.0) <= 1; }, 3000)) << "shown before a request";
    manager.note_request();
    EXPECT_TRUE(pump_until([&] { return (error = mix_error(desktop, ps, 0.5)) <= 3; }, 3000))
        << "not shown on a request: off by " << error;
    manager.hide_for_snapshot();
    EXPECT_TRUE(pump_until([&] { return mix_error(desktop, ps, 0.0) <= 1; }, 3000)) << "shown in a snapshot";
    manager.show_after_snapshot();
    EXPECT_TRUE(pump_until([&] { return mix_error(desktop, ps, 0.5) <= 3; }, 3000)) << "not back after a snapshot";
    EXPECT_EQ(active_window(env), backdrop_id);
}

void run_child(const std::string& child, const std::string& screen, const std::vector<std::string>& compositor,
               std::string& log, bool check_detection = false) {
    run_x11_child("OverlayWindowOnX.DISABLED_" + child, screen, compositor, log, check_detection);
}

// The child's overlay over openbox and a compositing manager, `compositor`.
void mixes_under(const std::vector<std::string>& compositor) {
    for (const char* program : {"xdotool", "xprop"})
        if (!find_program(program))
            GTEST_SKIP() << program << " is not installed (Debian: apt-get install -y xdotool x11-utils)";
    std::string log;
    run_child("Child", "1920x1080x24", compositor, log, true);
}

TEST(OverlayWindow, MixesIntoACompositedDesktop) { mixes_under({"xcompmgr"}); }

// picom, the compositor most X11 desktops without their own use; its
// software backend, since Xvfb has no GPU. No configuration file: no
// shadows or fading to blur the measured pixels.
TEST(OverlayWindow, MixesUnderPicom) {
    mixes_under({"picom", "--backend", "xrender", "--config", "/dev/null", "--no-fading-openclose"});
}

// A checkerboard of 2-pixel squares in root coordinates: as much
// high-frequency energy as a screen can hold.
bool pattern_white(int root_x, int root_y) { return ((root_x / 2) + (root_y / 2)) % 2 == 0; }

class PatternBackdrop : public QRasterWindow {
public:
    explicit PatternBackdrop(QSize root) : pattern_(root, QImage::Format_RGB32) {
        for (int y = 0; y < root.height(); ++y) {
            auto* row = reinterpret_cast<QRgb*>(pattern_.scanLine(y));
            for (int x = 0; x < root.width(); ++x) row[x] = pattern_white(x, y) ? qRgb(255, 255, 255) : qRgb(0, 0, 0);
        }
    }

protected:
    // Drawn where the window lies, so the screen shows the root's pattern.
    void paintEvent(QPaintEvent*) override {
        QPainter(this).drawImage(QPoint(0, 0), pattern_, QRect(mapToGlobal(QPoint(0, 0)), size()));
    }
    void moveEvent(QMoveEvent*) override { update(); }

private:
    QImage pattern_;
};

// The green channel of a capture.
int green(const Capture& shot, int x, int y) { return (shot.pixels[static_cast<std::size_t>(y) * shot.width + x] >> 8) & 255; }

// Mean absolute difference of horizontal and vertical neighbours.
double edge_energy(const Capture& shot) {
    double sum = 0;
    int n = 0;
    for (int y = 0; y + 1 < shot.height; ++y)
        for (int x = 0; x + 1 < shot.width; ++x) {
            sum += std::abs(green(shot, x + 1, y) - green(shot, x, y)) + std::abs(green(shot, x, y + 1) - green(shot, x, y));
            n += 2;
        }
    return n ? sum / n : 0;
}

// Pixels of `rect` off the pattern.
int off_pattern(const X11Desktop& desktop, QRect rect) {
    const Capture shot = desktop.capture({rect.x(), rect.y(), rect.width(), rect.height()});
    if (shot.pixels.size() != static_cast<std::size_t>(rect.width()) * rect.height()) return rect.width() * rect.height();
    int off = 0;
    for (int y = 0; y < shot.height; ++y)
        for (int x = 0; x < shot.width; ++x)
            off += green(shot, x, y) != (pattern_white(rect.x() + x, rect.y() + y) ? 255 : 0);
    return off;
}

// Only in the child: focus with a blur over the pattern.
TEST(OverlayWindowOnX, DISABLED_BlurChild) {
    if (!std::getenv(kChildVariable)) GTEST_SKIP() << "run by OverlayWindow.BlursTheDesktopUnderTheFocusCircle";
    X11ChildApplication child;
    ASSERT_EQ(QGuiApplication::platformName(), "xcb");
    const X11Desktop desktop(std::getenv("DISPLAY"));
    QScreen* screen = QGuiApplication::primaryScreen();

    PatternBackdrop backdrop(screen->geometry().size());
    backdrop.setFlags(Qt::Window | Qt::FramelessWindowHint);
    backdrop.setGeometry(screen->geometry());
    backdrop.show();
    const QRect probe(400, 300, 64, 64);
    ASSERT_TRUE(pump_until([&] { return off_pattern(desktop, probe) == 0; }, 5000)) << "the pattern is not shown";

    umf::overlay::Preset preset;
    preset.period_s = 0;
    preset.opacity_max = 0.5;
    preset.activation = umf::overlay::Activation::always;
    preset.region = umf::overlay::Region::focus;
    preset.focus_radius_modules = 4;
    preset.blur = 1.0;
    OverlayManager manager(preset);
    ASSERT_EQ(manager.screens().size(), 1u);
    const OverlayScreen s = manager.screens()[0];
    OverlayWindow& window = *manager.windows()[0];
    const double module = s.field.placement.module_px;
    const double radius = 4 * module;
    const QPointF centre(700.5, 520.5);
    manager.set_focus(s.index, centre);
    ASSERT_TRUE(pump_until([&] { return !window.backdrop_rect().isEmpty() && !manager.grab_pending(); }, 5000))
        << "no backdrop was grabbed";
    std::printf("grab cost: capture and blur %.2f ms for a %.0f px radius (%.0f px modules), backdrop %dx%d\n",
                manager.last_grab_cost_ms(), radius, module, window.backdrop_rect().width(),
                window.backdrop_rect().height());
    EXPECT_TRUE(window.painted_pulse());
    EXPECT_EQ(window.opacity(), 1.0);

    // Module centres well inside the circle, with their colours.
    const QImage layer = field_layer(s.field, {});
    std::vector<Probe> inside;
    for (int i = 0; i < s.field.field.height; ++i)
        for (int j = 0; j < s.field.field.width; ++j) {
            const auto p = umf::overlay::field_to_screen(s.field.placement, j + 0.5, i + 0.5);
            if (std::hypot(p.x - centre.x(), p.y - centre.y()) > 0.6 * radius) continue;
            const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
            if (qAlpha(layer.pixel(x, y)) == 255) inside.push_back({x, y, layer.pixel(x, y)});
        }
    ASSERT_GE(inside.size(), 12u);
    bool both = false;
    for (const Probe& p : inside) both |= p.colour != inside[0].colour;
    EXPECT_TRUE(both) << "one colour only in the circle";

    // The blurred checkerboard is its mean, 127.5: the field mixed into it.
    auto mixed_error = [&](double a) {
        int worst = 0;
        for (const Probe& p : inside) {
            const Capture shot = desktop.capture({p.x, p.y, 1, 1});
            if (shot.pixels.empty()) return 255;
            const std::uint32_t got = shot.pixels[0];
            const int pairs[3][2] = {{static_cast<int>((got >> 16) & 255), qRed(p.colour)},
                                     {static_cast<int>((got >> 8) & 255), qGreen(p.colour)},
                                     {static_cast<int>(got & 255), qBlue(p.colour)}};
            for (const auto& [screen_value, colour] : pairs)
                worst = std::max(worst, static_cast<int>(std::lround(std::abs(screen_value - ((1 - a) * 127.5 + a * colour)))));
        }
        return worst;
    };
    int error = 255;
    EXPECT_TRUE(pump_until([&] { return (error = mixed_error(0.5)) <= 4; }, 5000)) << "module centres off by " << error;

    // Blurred: far less edge energy in the circle than in the pattern, what
    // is left being the field's module edges.
    const int half = static_cast<int>(0.55 * radius);
    const QRect core(static_cast<int>(centre.x()) - half, static_cast<int>(centre.y()) - half, 2 * half, 2 * half);
    const double pattern_energy = edge_energy(desktop.capture({probe.x(), probe.y(), probe.width(), probe.height()}));
    const double circle_energy = edge_energy(desktop.capture({core.x(), core.y(), core.width(), core.height()}));
    std::printf("edge energy: pattern %.1f, circle %.1f\n", pattern_energy, circle_energy);
    EXPECT_GT(pattern_energy, 100.0);
    EXPECT_LT(circle_energy, 0.1 * pattern_energy);

    // Outside the circle the pattern, untouched: beside it and far away.
    const int r = static_cast<int>(std::ceil(radius)) + 2;
    for (const QRect rect : {QRect(static_cast<int>(centre.x()) + r, static_cast<int>(centre.y()) - 32, 64, 64),
                             QRect(static_cast<int>(centre.x()) - r - 64, static_cast<int>(centre.y()) - 32, 64, 64),
                             QRect(static_cast<int>(centre.x()) - 32, static_cast<int>(centre.y()) + r, 64, 64), probe,
                             QRect(1500, 800, 64, 64)})
        EXPECT_EQ(off_pattern(desktop, rect), 0) << "the pattern changed at " << rect.x() << "," << rect.y();

    // The painted pulse: another opacity reaches the screen by a repaint of
    // the circle, the window's own opacity still 1.
    const int paints = window.paint_count();
    window.set_opacity(0.25);
    EXPECT_TRUE(pump_until([&] { return (error = mixed_error(0.25)) <= 4; }, 5000)) << "module centres off by " << error;
    EXPECT_GT(window.paint_count(), paints);
    EXPECT_EQ(window.opacity(), 1.0);
    EXPECT_EQ(off_pattern(desktop, QRect(1500, 800, 64, 64)), 0);
}

TEST(OverlayWindow, BlursTheDesktopUnderTheFocusCircle) {
    std::string log;
    run_child("BlurChild", "1920x1080x24", {"xcompmgr"}, log);
    // The child's measurements, for the record.
    for (const char* key : {"grab cost:", "edge energy:"})
        if (const auto at = log.find(key); at != std::string::npos)
            std::cout << log.substr(at, log.find('\n', at) - at) << "\n";
}

// Only in the child: screens come and go (RandR 1.5 monitors, which Qt
// follows as screens), and one of them is twice as dense.
TEST(OverlayWindowOnX, DISABLED_ScreensChild) {
    if (!std::getenv(kChildVariable)) GTEST_SKIP() << "run by OverlayWindow.FollowsScreensAddedAndRemoved";
    X11ChildApplication child;
    ASSERT_EQ(QGuiApplication::platformName(), "xcb");
    const auto env = environment_with({});

    umf::overlay::Preset preset;
    preset.period_s = 0;
    preset.opacity_max = 0.5;
    preset.activation = umf::overlay::Activation::always;
    OverlayManager manager(preset);
    int changes = 0;
    manager.on_screens_changed([&] { ++changes; });
    ASSERT_EQ(manager.screens().size(), 1u);
    ASSERT_TRUE(manager.layout());
    EXPECT_EQ(manager.layout()->screens[0].screen.width, 3840);

    // Split into two: 96 dpi on the left, 192 dpi on the right.
    run({"xrandr", "--setmonitor", "L", "1920/508x1080/286+0+0", "screen"}, env);
    run({"xrandr", "--setmonitor", "R", "1920/254x1080/143+1920+0", "none"}, env);
    ASSERT_TRUE(pump_until([&] { return manager.screens().size() == 2; }, 5000))
        << manager.screens().size() << " screens";
    EXPECT_GE(changes, 1);
    auto screens = manager.screens();
    std::sort(screens.begin(), screens.end(), [](const auto& a, const auto& b) { return a.root_rect.x() < b.root_rect.x(); });
    EXPECT_EQ(screens[0].root_rect, QRect(0, 0, 1920, 1080));
    EXPECT_EQ(screens[1].root_rect, QRect(1920, 0, 1920, 1080));
    // Each window covers its screen and is shown.
    for (OverlayWindow* w : manager.windows()) {
        EXPECT_TRUE(w->isVisible());
        EXPECT_EQ(w->geometry().size(), QSize(1920, 1080));
    }
    // The denser screen shows modules twice as large, in its own part of the field.
    const auto& layout = *manager.layout();
    ASSERT_EQ(layout.screens.size(), 2u);
    const auto& left = layout.screens[0].screen.x == 0 ? layout.screens[0] : layout.screens[1];
    const auto& right = layout.screens[0].screen.x == 0 ? layout.screens[1] : layout.screens[0];
    EXPECT_NEAR(right.field.placement.module_px / left.field.placement.module_px, 2.0, 0.1);
    EXPECT_GE(left.field.placement.module_px, 30.0);
    EXPECT_TRUE(left.region.u1 <= right.region.u0 || right.region.u1 <= left.region.u0);
    EXPECT_EQ(manager.layout_indices().size(), 2u);

    // The right one goes: one screen again, the whole field for it.
    const int before = changes;
    run({"xrandr", "--delmonitor", "R"}, env);
    ASSERT_TRUE(pump_until([&] { return manager.screens().size() == 1; }, 5000));
    EXPECT_GT(changes, before);
    EXPECT_EQ(manager.screens()[0].root_rect, QRect(0, 0, 1920, 1080));
    EXPECT_EQ(manager.layout()->screens.size(), 1u);
    EXPECT_DOUBLE_EQ(manager.layout()->screens[0].field.placement.module_px, 30.0);
    EXPECT_EQ(manager.windows().size(), 1u);

    // A preset with larger modules relays the field out.
    const int before_preset = changes;
    preset.module_px = 40;
    manager.set_preset(preset);
    EXPECT_GT(changes, before_preset);
    EXPECT_DOUBLE_EQ(manager.layout()->screens[0].field.placement.module_px, 40.0);
    EXPECT_DOUBLE_EQ(manager.windows()[0]->screen_field().placement.module_px, 40.0);
}

TEST(OverlayWindow, FollowsScreensAddedAndRemoved) {
    if (!find_program("xrandr")) GTEST_SKIP() << "xrandr is not installed (Debian: apt-get install -y x11-xserver-utils)";
    std::string log;
    run_child("ScreensChild", "3840x1080x24", {"xcompmgr"}, log);
}

}  // namespace

#endif
