// The desktop provider for real: Xvfb with openbox and a compositing manager
// (xcompmgr), an xterm in the middle of the screen, and umf-provider mixing
// its field over the desktop. A screenshot of the desktop holds the field at
// the right place; umf-requester grabbing with that screenshot gets a
// snapshot of the xterm, and the snapshot holds no field (the overlay hides
// itself while the window is captured).
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "provider/desktop/x11/x11_desktop.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "shared/detect/detector.hpp"
#include "tests/provider/desktop_photo.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

using namespace umf::provider;
using namespace umf::test;

TEST(DesktopOverlay, TheFieldIsOverTheDesktopAndNotInSnapshots) {
    for (const char* program : {"Xvfb", "openbox", "xcompmgr", "xterm", "xdotool"})
        if (!find_program(program))
            GTEST_SKIP() << program << " is not installed (Debian: apt-get install xvfb openbox xcompmgr xterm xdotool)";
    TempDir dir("umf-desktop-overlay");
    const XServer server = start_xvfb(dir.path / "xvfb.log", "1920x1080x24");
    const auto env = environment_with({{"DISPLAY", server.display}, {"HOME", dir.path.string()},
                                       {"QT_QPA_PLATFORM", "xcb"}, {"XDG_CONFIG_HOME", (dir.path / "config").string()}});
    auto options = [&](const std::string& log) {
        Process::Options o;
        o.cwd = dir.path;
        o.env = env;
        o.log = dir.path / log;
        return o;
    };
    auto log_of = [&](const std::string& log) {
        std::ifstream in(dir.path / log);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const auto desktop = std::make_shared<const X11Desktop>(server.display);
    const auto openbox = start_openbox(options("openbox.log"), dir.path / "openbox-ready");
    ASSERT_TRUE(desktop->has_ewmh());
    Process compositor({"xcompmgr"}, options("xcompmgr.log"));
    // An xterm in grey over the screen's centre, placed once openbox manages it.
    std::unique_ptr<Process> xterm;
    unsigned long term = 0;
    for (int attempt = 0; attempt < 3 && !term; ++attempt) {
        xterm = std::make_unique<Process>(
            std::vector<std::string>{"xterm", "-bg", "#808080", "-fg", "#808080", "-T", "umf grey", "-e", "sleep", "60"},
            options("xterm.log"));
        const int pid = xterm->pid();
        wait_until(
            [&] {
                for (const auto& w : desktop->windows())
                    if (w.pid == pid) term = w.id;
                return term != 0;
            },
            5s);
    }
    ASSERT_NE(term, 0u) << "xterm showed no window";
    run({"xdotool", "windowsize", std::to_string(term), "600", "400", "windowmove", std::to_string(term), "660", "340"},
        env);
    ASSERT_TRUE(wait_until([&] { auto w = desktop->window_at(960, 540); return w && w->id == term; }, 5s));

    Process provider({UMF_PROVIDER_TOOL, "--port", "0", "--no-qr", "--config-dir", (dir.path / "cfg").string(),
                      "--preset", "visible"},
                     options("provider.log"));
    ASSERT_TRUE(wait_until([&] { return log_of("provider.log").find("overlay: 1 screen") != std::string::npos; }, 20s))
        << log_of("provider.log");
    const std::string url = pairing_url_in(log_of("provider.log"));
    ASSERT_FALSE(url.empty()) << log_of("provider.log");

    // The field over the desktop, where the provider says it is.
    const ScreenField field = screen_field_for(1920, 1080, 0.0, own_field_source(dir.path / "cfg"));  // what it shows
    const umf::Detector detector(field.field);
    const DesktopPhoto photo = capture_until_field(*desktop, detector, 1920, 1080, 20s);
    const umf::Detection& found = photo.detection;
    const cv::Mat& bgr = photo.bgr;
    ASSERT_TRUE(found.found) << "no field on the desktop: " << found.failure << "\n" << log_of("provider.log");
    double u = 0, v = 0;
    umf::overlay::screen_to_field(field.placement, 960, 540, u, v);
    EXPECT_NEAR(found.aim_field.x(), u, 0.05);
    EXPECT_NEAR(found.aim_field.y(), v, 0.05);

    // A grab with that screenshot: the xterm has no document, so a snapshot.
    const fs::path shot = dir.path / "desktop.png", out = dir.path / "received";
    cv::imwrite(shot.string(), bgr);
    const auto grabbed = run_command(std::string(UMF_REQUESTER_TOOL) + " grab --url '" + url + "' --image " +
                                     shot.string() + " --out " + out.string() + " 2>" + (dir.path / "grab.log").string());
    ASSERT_EQ(grabbed.exit_code, 0) << grabbed.out << log_of("grab.log");
    const auto result = nlohmann::json::parse(grabbed.out.substr(0, grabbed.out.find('\n')));
    EXPECT_EQ(result.value("kind", ""), "snapshot");
    EXPECT_EQ(result.value("title", "").find("umf grey"), 0u) << result.dump();
    const cv::Mat snapshot = cv::imread(result.value("saved", ""), cv::IMREAD_COLOR);
    ASSERT_FALSE(snapshot.empty());
    EXPECT_GE(snapshot.cols, 600);
    EXPECT_GE(snapshot.rows, 400);
    // The xterm is grey throughout (its text is grey on grey); with the field
    // mixed in, half its pixels would be darker or lighter by a third.
    long grey_pixels = 0, inside = 0;
    for (int y = snapshot.rows / 4; y < snapshot.rows * 3 / 4; ++y)
        for (int x = snapshot.cols / 4; x < snapshot.cols * 3 / 4; ++x) {
            const cv::Vec3b p = snapshot.at<cv::Vec3b>(y, x);
            ++inside;
            grey_pixels += std::abs(p[0] - 0x80) <= 3 && std::abs(p[1] - 0x80) <= 3 && std::abs(p[2] - 0x80) <= 3;
        }
    EXPECT_GT(grey_pixels, inside * 95 / 100) << "the snapshot holds the field";
    // SIGTERM ends it cleanly, its windows and the Qt loop included.
    ::kill(provider.pid(), SIGTERM);
    const auto status = provider.wait_exit(10s);
    ASSERT_TRUE(status) << "the provider did not stop";
    EXPECT_EQ(*status, 0) << log_of("provider.log");
    EXPECT_NE(log_of("provider.log").find("umf-provider: stopped"), std::string::npos);
}

}  // namespace

#endif
