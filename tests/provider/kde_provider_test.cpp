// The provider itself on a real KWin (5.27, Wayland, compositing with
// OpenGL on llvmpipe, as a desktop with a GPU does): its desktop entry
// written by `umf-provider kde install` into the session's data folder,
// umf-provider started in the session (the backend chosen from
// XDG_CURRENT_DESKTOP=KDE), three windows side by side (a native
// weston-image showing a picture, an Xwayland xterm showing a text file, a
// grey xterm), the field on the layer shell above them. The screen as KWin
// shows it (its ScreenShot2, to the test program its own entry grants it)
// holds the field where the provider says; umf-requester grabs with photos
// of it aimed at each window: the documents arrive byte for byte, the grey
// window as a snapshot without the field. Then KWin dies and the provider
// serves on.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "provider/desktop/kde/kde_desktop.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "shared/detect/detector.hpp"
#include "tests/provider/desktop_photo.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/support/files.hpp"
#include "tests/support/kwin_session.hpp"

namespace umf::provider {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

TEST(KdeProvider, TheProviderTakesDocumentsAndSnapshotsFromNativeAndXwaylandWindows) {
    if (const auto missing = test::kwin_missing()) GTEST_SKIP() << *missing;
    for (const char* program : {"xterm", "weston-image"})
        if (!test::find_program(program))
            GTEST_SKIP() << program << " is not installed (Debian: apt-get install -y xterm weston)";
    test::ensure_gui_application();
    test::KWinSession session = test::start_kwin({.opengl = true});
    // The test looks at the screen through KWin's screenshot interface, as
    // the provider does once its own entry is installed.
    test::install_application(session, "umf-tests", "/proc/self/exe", "org.kde.KWin.ScreenShot2");
    ASSERT_NO_THROW(test::run({UMF_PROVIDER_TOOL, "kde", "install"}, session.env()));
    ASSERT_TRUE(fs::exists(session.data_home() / "applications" / "umf-provider.desktop"));

    const fs::path work = session.dir->path / "work";
    fs::create_directories(work);
    // A picture for the native window: KWin's virtual output has no
    // physical size, and foot, the native terminal the other desktops'
    // tests use, divides by it.
    const fs::path notes = work / "notes.png", report = work / "report.txt";
    cv::imwrite(notes.string(), cv::Mat(300, 400, CV_8UC3, cv::Scalar(40, 160, 220)));
    std::ofstream(report) << "a report shown in an Xwayland window on KDE Plasma\n";

    KdeDesktopOptions options;
    options.bus_address = session.bus_address;
    options.wayland_display = (session.runtime / session.wayland_display).string();
    options.script_dir = session.dir->path / "scripts";
    const auto desktop = make_kde_desktop(options);
    // Side by side, each moved centred on its place as soon as it shows.
    const std::map<std::string, double> centres = {{"Wayland Image - notes.png", 330}, {"report.txt", 960}, {"plain grey", 1590}};
    std::vector<std::unique_ptr<test::Process>> clients;
    const auto open = [&](const std::string& title, const std::vector<std::string>& argv) {
        auto watch = desktop->watch_new_window(WindowPlacement{centres.at(title), 540, {0, 0, 1920, 1080}});
        ASSERT_TRUE(watch);
        clients.push_back(session.start_client(argv, title + ".log"));
        ASSERT_TRUE(watch->place(clients.back()->pid(), 10000ms)) << title << " was not placed:\n" << session.log();
    };
    open("Wayland Image - notes.png", {"weston-image", notes.string()});
    open("report.txt", {"xterm", "-geometry", "80x30", "-T", "report.txt", "-e", "less", report.string()});
    open("plain grey", {"xterm", "-geometry", "80x30", "-bg", "#808080", "-fg", "#808080", "-T", "plain grey"});
    std::map<std::string, WindowInfo> windows;
    ASSERT_TRUE(test::wait_until(
        [&] {
            for (const auto& [title, x] : centres)
                if (const auto w = desktop->window_at(x, 540, {}); w && w->title == title) windows[title] = *w;
            return windows.size() == centres.size();
        },
        15s))
        << "the three windows are not where they were put: " << [&] {
               std::string seen;
               for (const auto& [title, x] : centres)
                   if (const auto w = desktop->window_at(x, 540, {})) seen += "'" + w->title + "' ";
               return seen;
           }() << "\n" << session.log();

    // The provider, in the session's environment (Qt through Xwayland, as
    // on Sway; the field on KWin's layer shell).
    const fs::path log = work / "provider.log";
    auto env = session.env({{"QT_QPA_PLATFORM", "xcb"}, {"XDG_CONFIG_HOME", (work / "config").string()}});
    test::Process::Options provider_options;
    provider_options.env = env;
    provider_options.log = log;
    test::Process provider({UMF_PROVIDER_TOOL, "--port", "0", "--no-qr", "--preset", "static", "--puts", "never"},
                           provider_options);
    ASSERT_TRUE(test::wait_until([&] { return test::read_file(log).find("overlay: 1 screen") != std::string::npos; }, 30s))
        << test::read_file(log);
    EXPECT_NE(test::read_file(log).find("desktop: kde"), std::string::npos) << test::read_file(log);
    // Every ability: the window under the point, snapshots, placement.
    EXPECT_NE(test::read_file(log).find("desktop: kde (Wayland session (XDG_CURRENT_DESKTOP=KDE)): field, windows, "
                                        "snapshots, placement"),
              std::string::npos)
        << test::read_file(log);
    const std::string url = test::pairing_url_in(test::read_file(log));
    ASSERT_FALSE(url.empty()) << test::read_file(log);

    // The screen as a camera sees it: the field found where the provider puts it.
    const ScreenField field = screen_field_for(1920, 1080, 0.0, own_field_source(work / "config" / "umf"));  // its own
    const Detector detector(field.field);
    const test::DesktopPhoto photo = test::capture_until_field(*desktop, detector, 1920, 1080, 20s);
    ASSERT_TRUE(photo.detection.found) << "no field on the screen: " << photo.detection.failure << "\n"
                                       << test::read_file(log);
    test::expect_aim_at(photo.detection, field.placement, 960, 540);
    test::keep_screenshot(photo.bgr, "kde-desktop.png");

    test::expect_documents_and_a_snapshot(url, photo.bgr, windows, notes, report, work);
    EXPECT_NE(test::read_file(log).find("took \"Wayland Image - notes.png\""), std::string::npos) << test::read_file(log);

    // KWin dies: the provider's keeper serves on without a desktop, at the
    // same place (commands/desktop_keeper.hpp).
    ::kill(session.kwin->pid(), SIGKILL);
    test::expect_serving_on_without_a_desktop(log, url);
}

}  // namespace
}  // namespace umf::provider

#endif
