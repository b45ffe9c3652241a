// The put card and snapshots, for real: Xvfb with openbox and xcompmgr, a
// grey xterm in the middle of the screen, umf-provider over it, and
// umf-requester putting a file at the screen's centre, so the card asking
// about it lies over the xterm. Another requester's grab of the xterm gets a
// snapshot without the card (it steps aside while the window is captured,
// as the field does) and the card is back on the screen afterwards. Then
// the put is accepted with "open" through `umf-provider puts`: the file is
// uploaded and saved, and the window the (fake) xdg-open brings up lands
// centred on the place the phone pointed at. The card stays over the field
// throughout, though the field raises itself over new windows.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <thread>

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

// The card's face (put_prompt_window.cpp: rgb(30, 32, 36) nearly opaque)
// against the grey xterm and the field's light and dark modules.
bool card_dark(std::uint32_t pixel) {
    const int r = (pixel >> 16) & 255, g = (pixel >> 8) & 255, b = pixel & 255;
    return r < 50 && g < 50 && b < 56 && b >= r;
}

TEST(PutCardOnX, TheCardStaysOutOfSnapshotsAndTheOpenedFileLandsWherePointed) {
    for (const char* program : {"Xvfb", "openbox", "xcompmgr", "xterm"})
        if (!find_program(program))
            GTEST_SKIP() << program << " is not installed (Debian: apt-get install xvfb openbox xcompmgr xterm)";
    TempDir dir("umf-put-card");
    const XServer server = start_xvfb(dir.path / "xvfb.log", "1920x1080x24");
    // xdg-open opens anything as an xterm titled "umf opened".
    fs::create_directories(dir.path / "bin");
    std::ofstream(dir.path / "bin" / "xdg-open") << "#!/bin/sh\nexec xterm -T 'umf opened' -e sleep 60\n";
    fs::permissions(dir.path / "bin" / "xdg-open", fs::perms::owner_all);
    const char* path = std::getenv("PATH");
    const auto env = environment_with({{"DISPLAY", server.display}, {"HOME", dir.path.string()},
                                       {"QT_QPA_PLATFORM", "xcb"}, {"XDG_CONFIG_HOME", (dir.path / "config").string()},
                                       {"XDG_RUNTIME_DIR", dir.path.string()},
                                       {"PATH", (dir.path / "bin").string() + ":" + (path ? path : "/usr/bin:/bin")}});
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
    // Grey on grey, 1000 x 600 around the centre: the card beside the centre lies on it.
    Process xterm({"xterm", "-bg", "#808080", "-fg", "#808080", "-geometry", "120x40", "-T", "umf grey", "-e",
                   "sleep", "120"},
                  options("xterm.log"));
    unsigned long term = 0;
    ASSERT_TRUE(wait_until(
        [&] {
            for (const auto& w : desktop->windows())
                if (w.pid == xterm.pid()) term = w.id;
            return term != 0;
        },
        10s));
    run({"xdotool", "windowsize", std::to_string(term), "1000", "600", "windowmove", std::to_string(term), "460",
         "240"},
        env);
    ASSERT_TRUE(wait_until([&] { auto w = desktop->window_at(960, 540); return w && w->id == term; }, 5s));

    Process provider({UMF_PROVIDER_TOOL, "--port", "0", "--no-qr", "--config-dir", (dir.path / "cfg").string(),
                      "--preset", "visible", "--put-dir", (dir.path / "puts").string()},
                     options("provider.log"));
    ASSERT_TRUE(wait_until([&] { return log_of("provider.log").find("overlay: 1 screen") != std::string::npos; }, 20s))
        << log_of("provider.log");
    const std::string url = pairing_url_in(log_of("provider.log"));
    ASSERT_FALSE(url.empty()) << log_of("provider.log");

    // A photo of the screen with the field, as both requesters' camera.
    const ScreenField field = screen_field_for(1920, 1080, 0.0, own_field_source(dir.path / "cfg"));  // what it shows
    const umf::Detector detector(field.field);
    const DesktopPhoto photo = capture_until_field(*desktop, detector, 1920, 1080, 20s);
    const umf::Detection& found = photo.detection;
    const cv::Mat& bgr = photo.bgr;
    ASSERT_TRUE(found.found) << "no field on the desktop: " << found.failure << "\n" << log_of("provider.log");
    const fs::path shot = dir.path / "desktop.png";
    cv::imwrite(shot.string(), bgr);

    // The put waits for an answer that never comes: the card stays up.
    std::ofstream(dir.path / "notes.txt") << "for the screen\n";
    Process put({UMF_REQUESTER_TOOL, "put", (dir.path / "notes.txt").string(), "--url", url, "--image", shot.string(),
                 "--no-window"},
                options("put.log"));
    // Where the card is: dark pixels below and right of the centre.
    const WindowRect card_area{960, 540, 300, 100};
    auto card_pixels = [&] {
        const Capture c = desktop->capture(card_area);
        return std::count_if(c.pixels.begin(), c.pixels.end(), card_dark);
    };
    ASSERT_TRUE(wait_until([&] { return card_pixels() > 300 * 100 / 4; }, 10s))
        << "no card on the screen\n" << log_of("put.log") << log_of("provider.log");
    // The field raises itself over new windows once a second; the card goes
    // over it again each time (the field over it leaves ~20 % dark, the
    // card alone ~56 %).
    auto fewest_card_pixels_over = [&](std::chrono::milliseconds span) {
        long fewest = card_pixels();
        for (const auto end = std::chrono::steady_clock::now() + span; std::chrono::steady_clock::now() < end;) {
            std::this_thread::sleep_for(100ms);
            fewest = std::min<long>(fewest, card_pixels());
        }
        return fewest;
    };
    EXPECT_GT(fewest_card_pixels_over(1500ms), 300 * 100 * 45 / 100) << "the field covered the card";

    const fs::path out = dir.path / "received";
    const auto grabbed = run_command(std::string(UMF_REQUESTER_TOOL) + " grab --url '" + url + "' --image " +
                                     shot.string() + " --out " + out.string() + " 2>" + (dir.path / "grab.log").string());
    ASSERT_EQ(grabbed.exit_code, 0) << grabbed.out << log_of("grab.log");
    const auto result = nlohmann::json::parse(grabbed.out.substr(0, grabbed.out.find('\n')));
    ASSERT_EQ(result.value("kind", ""), "snapshot") << result.dump();
    const cv::Mat snapshot = cv::imread(result.value("saved", ""), cv::IMREAD_COLOR);
    ASSERT_FALSE(snapshot.empty());
    ASSERT_GE(snapshot.cols, 1000);
    ASSERT_GE(snapshot.rows, 600);
    // The snapshot's (500, 300) is the screen's centre: where the card was,
    // grey xterm only.
    long dark = 0, grey = 0;
    for (int y = 300; y < 400; ++y)
        for (int x = 500; x < 800; ++x) {
            const cv::Vec3b p = snapshot.at<cv::Vec3b>(y, x);
            dark += card_dark(0xff000000u | (p[2] << 16) | (p[1] << 8) | p[0]);
            grey += std::abs(p[0] - 0x80) <= 3 && std::abs(p[1] - 0x80) <= 3 && std::abs(p[2] - 0x80) <= 3;
        }
    EXPECT_EQ(dark, 0) << "the card is in the snapshot";
    EXPECT_GT(grey, 300 * 100 * 95 / 100) << "the snapshot holds the card or the field";
    // Back on the screen, still asking.
    EXPECT_TRUE(wait_until([&] { return card_pixels() > 300 * 100 / 4; }, 5s)) << "the card did not come back";
    EXPECT_GT(fewest_card_pixels_over(1500ms), 300 * 100 * 45 / 100) << "the field covered the card that came back";
    EXPECT_NE(log_of("provider.log").find(": asking the screen"), std::string::npos) << log_of("provider.log");

    // Accepted with "open" at the screen (the control socket answers as the card would).
    const std::string port = url.substr(url.rfind(':') + 1, url.find('/', url.rfind(':')) - url.rfind(':') - 1);
    ASSERT_FALSE(port.empty()) << url;
    Process accept({UMF_PROVIDER_TOOL, "puts", "--accept", "1", "--open", "--port", port}, options("accept.log"));
    ASSERT_EQ(accept.wait_exit(10s), 0) << log_of("accept.log");
    ASSERT_EQ(put.wait_exit(20s), 0) << log_of("put.log");
    EXPECT_EQ(log_of((fs::path("puts") / "notes.txt").string()), "for the screen\n");
    std::optional<WindowInfo> opened;
    EXPECT_TRUE(wait_until(
        [&] {
            opened.reset();
            for (const auto& w : desktop->windows())
                if (w.title == "umf opened") opened = w;
            return opened && std::abs(opened->rect.x + opened->rect.width / 2 - 960) <= 4 &&
                   std::abs(opened->rect.y + opened->rect.height / 2 - 540) <= 4;
        },
        10s))
        << (opened ? "opened at " + std::to_string(opened->rect.x) + "," + std::to_string(opened->rect.y)
                   : std::string("nothing opened"))
        << "\n" << log_of("provider.log");
    EXPECT_NE(log_of("provider.log").find("\u2192 saved as " + (dir.path / "puts" / "notes.txt").string() + " and opened"),
              std::string::npos)
        << log_of("provider.log");
}

}  // namespace

#endif
