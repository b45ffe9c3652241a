// The field's layer surface (the one the wlroots backend makes; KWin offers
// the same layer shell) on a real KWin compositing with OpenGL (llvmpipe),
// as the provider shows it there: over a native Wayland window (weston-image)
// and an Xwayland one (xterm), seen through KWin's screenshot interface and
// clicked through with KWin's fake input, both of which the test program's
// desktop file lets it use.
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QImage>
#include <cmath>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <thread>

#include "provider/desktop/kde/kde_desktop.hpp"
#include "provider/desktop/kde/kwin_scripting.hpp"
#include "provider/screen/board_window.hpp"
#include "provider/desktop/wlroots/layer_field_surface.hpp"
#include "provider/screen/screen_field.hpp"
#include "tests/provider/field_on_screen.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/support/kwin_fake_pointer.hpp"
#include "tests/support/kwin_session.hpp"

namespace umf::provider {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

constexpr int kWidth = 1920, kHeight = 1080;

using test::pump;

class KdeField : public ::testing::Test {
protected:
    void SetUp() override {
        if (const auto missing = test::kwin_missing()) GTEST_SKIP() << *missing;
        for (const char* program : {"xterm", "weston-image"})
            if (!test::find_program(program))
                GTEST_SKIP() << program << " is not installed (Debian: apt-get install -y xterm weston)";
        test::ensure_gui_application();
        session_ = std::make_unique<test::KWinSession>(test::start_kwin({.opengl = true}));
        test::install_application(*session_, "umf-tests", "/proc/self/exe", "org.kde.KWin.ScreenShot2",
                                  "org_kde_kwin_fake_input");
        KdeDesktopOptions options;
        options.bus_address = session_->bus_address;
        options.wayland_display = (session_->runtime / session_->wayland_display).string();
        options.script_dir = session_->dir->path / "scripts";
        options.layer_surface = [](const std::string& display, QScreen* screen, ScreenField field,
                                   const std::vector<std::string>& palette) -> std::unique_ptr<FieldSurface> {
            return LayerFieldSurface::create(display, screen, std::move(field), palette);
        };
        desktop_ = make_kde_desktop(options);

        // A picture in a native window on the left, an xterm on the right.
        const fs::path picture = session_->dir->path / "picture.png";
        cv::Mat image(500, 700, CV_8UC3);
        for (int y = 0; y < image.rows; ++y)
            for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x) = {uchar(x / 3), uchar(y / 2), 200};
        cv::imwrite(picture.string(), image);
        open({"weston-image", picture.string()}, 500, "image.log");
        open({"xterm", "-geometry", "80x30", "-bg", "#406080", "-T", "umf-xterm", "-e", "sleep", "120"}, 1400, "xterm.log");
        // KWin has read the test program's desktop file, and both windows are drawn.
        ASSERT_TRUE(test::wait_until(
            [&] {
                try {
                    shot();
                    return true;
                } catch (const DesktopError&) {
                    return false;
                }
            },
            30s))
            << "KWin gave the test program no screenshot";
        std::this_thread::sleep_for(500ms);
    }

    // Started and moved centred on (x, 540).
    void open(const std::vector<std::string>& argv, double x, const std::string& log) {
        auto watch = desktop_->watch_new_window(WindowPlacement{x, 540, {0, 0, kWidth, kHeight}});
        ASSERT_TRUE(watch);
        clients_.push_back(session_->start_client(argv, log));
        const auto id = watch->place(clients_.back()->pid(), 10000ms);
        ASSERT_TRUE(id) << argv[0] << " was not placed:\n" << session_->log();
        const auto window = desktop_->window_at(x, 540, {});
        ASSERT_TRUE(window && window->id == *id) << argv[0];
        windows_.push_back(window->rect);
    }

    // The whole screen as KWin shows it.
    QImage shot() const {
        const Capture capture = desktop_->capture({0, 0, kWidth, kHeight});
        QImage image(capture.width, capture.height, QImage::Format_RGB32);
        for (int y = 0; y < capture.height; ++y)
            std::copy_n(capture.pixels.data() + static_cast<std::size_t>(y) * capture.width, capture.width,
                        reinterpret_cast<std::uint32_t*>(image.scanLine(y)));
        return image;
    }

    // The whole output's field at `opacity`, once its first frame is committed.
    void show_field(double opacity, std::unique_ptr<FieldSurface>& made) {
        made = desktop_->make_field_surface(nullptr, screen_field_for(kWidth, kHeight), {});
        ASSERT_TRUE(made);
        auto& surface = dynamic_cast<LayerFieldSurface&>(*made);
        surface.set_opacity(opacity);
        surface.show();
        ASSERT_TRUE(test::wait_until([&] { pump(surface, 20ms); return surface.frames_committed() > 0; }, 5s));
        pump(surface, 300ms);
    }

    // The caption of KWin's active window (KWin 5.27 names it
    // activeClient, KWin 6 activeWindow).
    std::string active_caption() {
        if (!scripting_) {
            const fs::path folder = session_->dir->path / "test-scripts";
            fs::create_directories(folder);
            scripting_ = std::make_unique<KWinScripting>(kde_bus_connection(session_->bus_address), folder);
        }
        return scripting_->run("var w = workspace.activeWindow || workspace.activeClient;\n"
                               "umfAnswer(w ? w.caption : \"\");\n",
                               2000ms);
    }

    std::unique_ptr<test::KWinSession> session_;
    std::unique_ptr<KWinScripting> scripting_;
    std::unique_ptr<Desktop> desktop_;
    std::vector<std::unique_ptr<test::Process>> clients_;
    std::vector<WindowRect> windows_;  // the picture's, the xterm's
};

QRect rect_of(const WindowRect& r) { return QRect(r.x, r.y, r.width, r.height); }

TEST_F(KdeField, ShowsAtItsOpacityOverNativeAndXwaylandWindowsAndGoesWhenHidden) {
    EXPECT_TRUE(desktop_->abilities().field);
    const QImage before = shot();
    constexpr double kOpacity = 0.25;
    std::unique_ptr<FieldSurface> made;
    ASSERT_NO_FATAL_FAILURE(show_field(kOpacity, made));
    auto& surface = dynamic_cast<LayerFieldSurface&>(*made);
    const QImage with = shot();
    const QImage layer = field_layer(surface.screen_field(), {});
    // A pixel moves by opacity * (module - under) at most, plus rounding:
    // translucent, the windows show through.
    const int worst = test::largest_change(before, with, QRect(0, 0, kWidth, kHeight));
    EXPECT_LE(worst, static_cast<int>(std::ceil(kOpacity * 255)) + 2);
    for (const auto& [window, name] : {std::pair{windows_[0], "the native window"}, std::pair{windows_[1], "the xterm"}}) {
        const test::FieldChange change = test::field_change(before, with, layer, rect_of(window));
        std::cout << "field at " << kOpacity << " over " << name << ": " << change.changed << " of "
                  << change.field_pixels << " field pixels changed by 8 or more\n";
        EXPECT_GT(change.changed, change.field_pixels / 4) << "the field should show over " << name;
    }

    surface.hide();
    pump(surface, 300ms);
    ASSERT_TRUE(test::wait_until([&] { return test::largest_change(before, shot(), QRect(0, 0, kWidth, kHeight), 3) <= 2; }, 3s))
        << "hidden, the field stays on the screen";
}

TEST_F(KdeField, ClicksGoThroughTheFieldToTheWindowsBelow) {
    std::unique_ptr<FieldSurface> made;
    ASSERT_NO_FATAL_FAILURE(show_field(0.25, made));
    auto& surface = dynamic_cast<LayerFieldSurface&>(*made);
    const std::string display = (session_->runtime / session_->wayland_display).string();
    std::unique_ptr<test::KWinFakePointer> pointer;
    ASSERT_TRUE(test::wait_until(
        [&] {
            pointer = std::make_unique<test::KWinFakePointer>(display);
            return pointer->available();
        },
        30s))
        << "KWin offers the test program no fake input";
    // A click on each window in turn makes it the active one: the field
    // above both takes none of them.
    const std::pair<WindowRect, std::string> clicks[] = {
        {windows_[1], "umf-xterm"}, {windows_[0], "Wayland Image - picture.png"}, {windows_[1], "umf-xterm"}};
    for (const auto& [window, caption] : clicks) {
        pointer->click(window.x + window.width / 2.0, window.y + window.height / 2.0);
        pump(surface, 50ms);
        std::string active;
        EXPECT_TRUE(test::wait_until([&] { return (active = active_caption()) == caption; }, 3s))
            << "a click on " << caption << " left " << active << " active";
    }
    surface.hide();
}

TEST_F(KdeField, ThePointerRingAndTitleAreDrawnAtFullStrengthOverAFaintField) {
    std::unique_ptr<FieldSurface> made;
    ASSERT_NO_FATAL_FAILURE(show_field(0.1, made));
    auto& surface = dynamic_cast<LayerFieldSurface&>(*made);
    const QPointF point(500, 540);  // on the native window
    const QImage before = shot();
    surface.set_aim_mark(point, "Report");
    pump(surface, 300ms);
    const QImage with = shot();
    const auto [bright, dark] = test::ring_extremes(with, point);
    EXPECT_GE(bright, 235) << "no white ring at full strength";
    EXPECT_LE(dark, 60) << "no dark outline";
    // The title beside it, white on its outline; none before.
    EXPECT_GE(test::white_title_pixels(with, point, "Report"), 20) << "no title beside the ring";
    EXPECT_EQ(test::white_title_pixels(before, point, "Report"), 0);
    // Away from the ring and title the field stays as faint as it was.
    EXPECT_LE(test::largest_change(before, with, QRect(100, 850, 1700, 200), 7), 2) << "the ring changed the field elsewhere";

    // Moved onto the xterm, then gone: nothing of it stays behind.
    surface.set_aim_mark(QPointF(1400, 540), "Report");
    pump(surface, 300ms);
    EXPECT_GE(test::ring_extremes(shot(), QPointF(1400, 540)).first, 235) << "no ring over the xterm";
    surface.set_aim_mark(std::nullopt, {});
    pump(surface, 300ms);
    EXPECT_LE(test::largest_change(before, shot(), QRect(400, 480, 1100, 140)), 2) << "the ring left pixels behind";
    surface.hide();
}

}  // namespace
}  // namespace umf::provider

#endif
