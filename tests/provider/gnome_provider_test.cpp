// The provider itself on a real headless GNOME Shell 43 with the umf
// extension: umf-provider started in the session as its user (the backend
// chosen from XDG_CURRENT_DESKTOP=GNOME), three windows placed side by side
// (a native foot showing a text file, an Xwayland xterm showing another, a
// grey foot), the field drawn by the extension above them. The screen as a
// camera sees it (the extension's ScreenAsShown) holds the field where the
// provider says; umf-requester grabs with photos of it aimed at each window:
// the documents arrive byte for byte, the grey window as a snapshot without
// the field.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "provider/desktop/gnome/gnome_desktop.hpp"
#include "provider/desktop/gnome/gnome_shell_client.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "shared/detect/detector.hpp"
#include "tests/provider/desktop_photo.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/support/files.hpp"
#include "tests/support/gnome_session.hpp"

namespace umf::provider {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

TEST(GnomeProvider, TheProviderTakesDocumentsAndSnapshotsFromNativeAndXwaylandWindows) {
    if (const auto why = test::GnomeSession::unavailable()) GTEST_SKIP() << *why;
    test::GnomeSession session;
    test::ensure_gui_application();
    ::setenv("DBUS_SESSION_BUS_ADDRESS", session.bus_address().c_str(), 1);
    ::setenv("XDG_RUNTIME_DIR", session.run_dir().c_str(), 1);
    // The extension answers its own user only: the connection is made as it
    // (and captures, which read the user's private folder, run as it).
    std::unique_ptr<GnomeDesktop> owned;
    {
        test::AsUser as(session.uid(), session.gid());
        owned = std::make_unique<GnomeDesktop>();
        ASSERT_TRUE(test::wait_until([&] { return owned->abilities().field; }, 20s)) << session.log();
    }
    GnomeDesktop& desktop = *owned;
    ASSERT_TRUE(session.leave_overview());

    const fs::path work = session.home() / "work";
    fs::create_directories(work);
    const fs::path notes = work / "notes.txt", report = work / "report.txt";
    std::ofstream(notes) << "notes from a native Wayland window on GNOME\n";
    std::ofstream(report) << "a report shown in an Xwayland window on GNOME\n";
    for (const auto& p : {work, notes, report})
        ASSERT_EQ(::chown(p.c_str(), session.uid(), session.gid()), 0) << p << ": " << std::strerror(errno);
    const auto x = session.xwayland();
    ASSERT_TRUE(x) << "no Xwayland in the session";
    const std::map<std::string, std::string> x11 = {{"DISPLAY", x->first}, {"XAUTHORITY", x->second}};
    const auto foot = session.start_client({"foot", "-W", "70x30", "-T", "notes.txt", "less", notes.string()}, "foot.log");
    const auto xterm = session.start_client({"xterm", "-geometry", "80x30", "-T", "report.txt", "-e", "less", report.string()}, "xterm.log", x11);
    const auto grey = session.start_client({"foot", "-W", "70x30", "-o", "colors.background=808080", "-o",
                                            "colors.foreground=808080", "-T", "plain grey", "sleep", "120"},
                                           "grey.log");
    // Side by side, each where it is asked to be (Mutter may still place a
    // new window after a move: moved until it stays).
    const std::map<std::string, int> lefts = {{"notes.txt", 30}, {"report.txt", 660}, {"plain grey", 1290}};
    std::map<std::string, WindowInfo> windows;
    ASSERT_TRUE(test::wait_until(
        [&] {
            windows.clear();
            for (const auto& w : desktop.shell().windows()) windows[w.title] = w;
            bool placed = true;
            for (const auto& [title, left] : lefts) {
                const auto it = windows.find(title);
                if (it == windows.end() || it->second.rect.empty()) return false;
                if (it->second.rect.x != left || it->second.rect.y != 200) {
                    desktop.shell().move_window(it->second.id, left, 200);
                    placed = false;
                }
            }
            return placed;
        },
        30s))
        << "the three windows were not placed:\n" << session.log();

    // The provider, as the session's user, in the session's environment.
    const fs::path log = work / "provider.log";
    auto env = x11;
    env["QT_QPA_PLATFORM"] = "xcb";
    env["XDG_CURRENT_DESKTOP"] = "GNOME";
    env["XDG_SESSION_TYPE"] = "wayland";
    env["XDG_CONFIG_HOME"] = (work / "config").string();
    const auto provider = session.start_client(
        {"sh", "-c", std::string("exec ") + UMF_PROVIDER_TOOL + " --port 0 --no-qr --preset static --puts never > " +
                         log.string() + " 2>&1"},
        "provider-start.log", env);
    ASSERT_TRUE(test::wait_until([&] { return test::read_file(log).find("overlay: 1 screen") != std::string::npos; }, 30s))
        << test::read_file(log);
    EXPECT_NE(test::read_file(log).find("desktop: gnome"), std::string::npos) << test::read_file(log);
    const std::string url = test::pairing_url_in(test::read_file(log));
    ASSERT_FALSE(url.empty()) << test::read_file(log);

    // The screen as a camera sees it: the field found where the provider puts it.
    const ScreenField field = screen_field_for(1920, 1080, 0.0, own_field_source(work / "config" / "umf"));  // its own
    const Detector detector(field.field);
    const test::DesktopPhoto photo = test::capture_until_field(
        [&](const WindowRect& r) {
            test::AsUser as(session.uid(), session.gid());
            return desktop.capture_as_shown(r);
        },
        detector, 1920, 1080, 20s);
    ASSERT_TRUE(photo.detection.found) << "no field on the screen: " << photo.detection.failure << "\n" << test::read_file(log);
    test::expect_aim_at(photo.detection, field.placement, 960, 540);
    test::keep_screenshot(photo.bgr, "gnome-desktop.png");

    test::expect_documents_and_a_snapshot(url, photo.bgr, windows, notes, report, work);
    EXPECT_NE(test::read_file(log).find("took \"notes.txt\""), std::string::npos) << test::read_file(log);
}

}  // namespace
}  // namespace umf::provider

#endif
