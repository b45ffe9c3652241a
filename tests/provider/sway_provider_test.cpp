// The provider itself on a real headless Sway: umf-provider started in the
// session as its user (--desktop chosen from SWAYSOCK and
// XDG_CURRENT_DESKTOP), three windows tiled side by side (a native foot
// showing a text file, an Xwayland xterm showing another, a plain grey foot),
// the field on the overlay layer above them. umf-requester grabs with
// screenshots of the desktop cropped around each window: the two documents
// arrive byte for byte, the grey window as a snapshot without the field.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "provider/desktop/wlroots/wlroots_desktop.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "shared/detect/detector.hpp"
#include "tests/provider/desktop_photo.hpp"
#include "tests/support/files.hpp"
#include "tests/support/process.hpp"
#include "tests/support/sway_session.hpp"

namespace umf::provider {
namespace {

using namespace std::chrono_literals;
using test::SwaySession;
namespace fs = std::filesystem;

TEST(SwayProvider, TheProviderTakesDocumentsAndSnapshotsFromNativeAndXwaylandWindows) {
    if (const auto why = SwaySession::cannot_run()) GTEST_SKIP() << *why;
    SwaySession sway;
    // Files the test user's programs show, and a folder the provider writes.
    const fs::path work = sway.dir() / "work";
    fs::create_directory(work);
    fs::permissions(work, fs::perms::all);
    const fs::path notes = work / "notes.txt", report = work / "report.txt";
    std::ofstream(notes) << "notes from a native Wayland window\n";
    std::ofstream(report) << "a report shown in an Xwayland window\n";
    for (const auto& f : {notes, report}) fs::permissions(f, fs::perms::owner_all | fs::perms::others_read);

    const auto foot = sway.start_client({"foot", "-T", "notes.txt", "less", notes.string()});
    const auto xterm = sway.start_client({"xterm", "-T", "report.txt", "-e", "less", report.string()});
    const auto plain = sway.start_client({"foot", "-o", "colors.background=808080", "-o", "colors.foreground=808080",
                                          "-T", "plain grey", "sleep", "120"});
    const auto desktop =
        make_wlroots_desktop(WlrootsSockets{sway.wayland_socket(), sway.swaysock(), {}, sway.runtime_dir()});
    std::map<std::string, WindowInfo> windows;
    ASSERT_TRUE(test::wait_until(
        [&] {
            auto* wl = dynamic_cast<WlrootsDesktop*>(desktop.get());
            windows.clear();
            for (const auto& w : wl->windows()) windows[w.title] = w;
            return windows.count("notes.txt") && windows.count("report.txt") && windows.count("plain grey");
        },
        15s))
        << "the three windows did not come up:\n" << sway.log();

    // The provider, as the session's user, in the session's environment.
    const fs::path log = work / "provider.log";
    std::ofstream(log).close();
    fs::permissions(log, fs::perms::all);
    const auto provider = sway.start_client(
        {"sh", "-c",
         "exec env QT_QPA_PLATFORM=xcb XDG_CURRENT_DESKTOP=sway XDG_SESSION_TYPE=wayland XDG_CONFIG_HOME=" +
             (work / "config").string() + " " + UMF_PROVIDER_TOOL + " --port 0 --no-qr --preset static --puts never > " +
             log.string() + " 2>&1"});
    ASSERT_TRUE(test::wait_until([&] { return test::read_file(log).find("overlay: 1 screen") != std::string::npos; }, 20s))
        << test::read_file(log);
    EXPECT_NE(test::read_file(log).find("desktop: wlroots"), std::string::npos) << test::read_file(log);
    const std::string url = test::pairing_url_in(test::read_file(log));
    ASSERT_FALSE(url.empty()) << test::read_file(log);

    // The desktop as a camera would see it, with the field found in it.
    const ScreenField field = screen_field_for(1920, 1080, 0.0, own_field_source(work / "config" / "umf"));  // its own
    const Detector detector(field.field);
    const test::DesktopPhoto photo = test::capture_until_field(*desktop, detector, 1920, 1080, 10s);
    ASSERT_TRUE(photo.detection.found) << "no field on the desktop: " << photo.detection.failure << "\n" << test::read_file(log);
    const cv::Mat& bgr = photo.bgr;

    // The README's picture of the provider on Sway (scripts/screenshots-wayland.sh).
    test::keep_screenshot(bgr, "sway-desktop.png");

    // Each window in the middle of a photo of its own.
    const cv::Mat snapshot = test::expect_documents_and_a_snapshot(url, bgr, windows, notes, report, work);
    ASSERT_FALSE(snapshot.empty());
    EXPECT_NEAR(snapshot.cols, windows["plain grey"].rect.width, 2);
    EXPECT_NEAR(snapshot.rows, windows["plain grey"].rect.height, 2);
    EXPECT_NE(test::read_file(log).find("took \"notes.txt\""), std::string::npos) << test::read_file(log);

    // The compositor dies: the console says the field is off, at once. Qt's
    // own connection goes through Xwayland, which dies with it, and ends the
    // desktop provider; its keeper serves on without a desktop, at the same
    // place (commands/desktop_keeper.hpp).
    ::kill(sway.sway().pid(), SIGKILL);
    EXPECT_TRUE(test::wait_until(
        [&] { return test::read_file(log).find("the connection to the Wayland compositor broke") != std::string::npos; }, 5s))
        << test::read_file(log);
    test::expect_serving_on_without_a_desktop(log, url);
}

}  // namespace
}  // namespace umf::provider

#endif
