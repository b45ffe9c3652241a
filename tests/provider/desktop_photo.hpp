// For tests of the provider on a real desktop (X11, Sway, GNOME): the
// pairing URL from its log, the desktop captured until the field shows, as a
// photo both requesters can be given (BGR for the webcam requester's
// --image, and the detection on it), photos aimed at one window, and a grab
// with the real umf-requester.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <tuple>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "provider/desktop/desktop.hpp"
#include "shared/detect/detector.hpp"
#include "shared/overlay/placement.hpp"
#include "tests/support/files.hpp"
#include "tests/support/process.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::test {

// The URL after "pairing URL: " in a provider's output, or "".
inline std::string pairing_url_in(const std::string& log) {
    const std::string label = "pairing URL: ";
    const auto at = log.find(label);
    if (at == std::string::npos) return "";
    const auto start = at + label.size();
    return log.substr(start, log.find('\n', start) - start);
}

struct DesktopPhoto {
    cv::Mat bgr;               // the whole desktop
    umf::Detection detection;  // the field found in it, or why not
};

// Captures width x height from the desktop's origin with `capture` until
// `detector` finds the field in it (the overlay pulses, so one capture may
// fall on its faint phase) or `timeout` passes; the last capture either way.
inline DesktopPhoto capture_until_field(const std::function<umf::provider::Capture(const umf::provider::WindowRect&)>& capture,
                                        const umf::Detector& detector, int width, int height,
                                        std::chrono::milliseconds timeout) {
    DesktopPhoto photo;
    photo.bgr.create(height, width, CV_8UC3);
    std::vector<std::uint8_t> grey(static_cast<std::size_t>(width) * height);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        umf::provider::Capture shot;
        try {
            shot = capture({0, 0, width, height});
        } catch (const std::exception&) {
        }
        if (shot.pixels.size() == grey.size()) {
            for (std::size_t i = 0; i < grey.size(); ++i) {
                const std::uint32_t p = shot.pixels[i];
                const std::uint8_t r = (p >> 16) & 255, g = (p >> 8) & 255, b = p & 255;
                grey[i] = static_cast<std::uint8_t>((r * 77 + g * 150 + b * 29) >> 8);
                photo.bgr.at<cv::Vec3b>(static_cast<int>(i / width), static_cast<int>(i % width)) = {b, g, r};
            }
            photo.detection = detector.detect(umf::GreyView{grey.data(), width, height, width});
            if (photo.detection.found) return photo;
        }
        if (std::chrono::steady_clock::now() >= deadline) return photo;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

// The same through the desktop's own capture (which shows the field on X11
// and wlroots, where the overlay is what the screen shows).
inline DesktopPhoto capture_until_field(const umf::provider::Desktop& desktop, const umf::Detector& detector, int width,
                                        int height, std::chrono::milliseconds timeout) {
    return capture_until_field([&](const umf::provider::WindowRect& r) { return desktop.capture(r); }, detector, width,
                               height, timeout);
}

// The square photo of `bgr` (the whole desktop) centred on `window` as far
// as the desktop allows, at most `side` pixels, written to `path`: a camera
// aimed at the window's middle.
inline std::filesystem::path photo_of_window(const cv::Mat& bgr, const umf::provider::WindowRect& window,
                                             const std::filesystem::path& path, int side = 560) {
    side = std::min({side, window.width, window.height});
    const int cx = window.x + window.width / 2, cy = window.y + window.height / 2;
    const cv::Rect crop(std::clamp(cx - side / 2, 0, bgr.cols - side), std::clamp(cy - side / 2, 0, bgr.rows - side),
                        side, side);
    cv::imwrite(path.string(), bgr(crop));
    return path;
}

// umf-requester grab --image `photo`: the JSON line it prints, or null with
// a test failure saying why.
inline nlohmann::json requester_grab(const std::string& url, const std::filesystem::path& photo,
                                     const std::filesystem::path& out) {
    const std::filesystem::path errors = out.string() + ".log";
    const auto result = run_command(std::string(UMF_REQUESTER_TOOL) + " grab --url '" + url + "' --image " +
                                    photo.string() + " --out " + out.string() + " 2>" + errors.string());
    std::ifstream in(errors);
    const std::string log{std::istreambuf_iterator<char>(in), {}};
    EXPECT_EQ(result.exit_code, 0) << result.out << log;
    try {
        return nlohmann::json::parse(result.out.substr(0, result.out.find('\n')));
    } catch (const std::exception&) {
        ADD_FAILURE() << "no JSON from the requester: " << result.out << log;
        return nlohmann::json::object();
    }
}

// The share of the middle half of `image` within 3 of grey `level` in every
// channel: 1 for a flat grey window, far less with the field mixed in.
inline double grey_share(const cv::Mat& image, int level = 0x80) {
    long grey = 0, inside = 0;
    for (int y = image.rows / 4; y < image.rows * 3 / 4; ++y)
        for (int x = image.cols / 4; x < image.cols * 3 / 4; ++x) {
            const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
            ++inside;
            grey += std::abs(p[0] - level) <= 3 && std::abs(p[1] - level) <= 3 && std::abs(p[2] - level) <= 3;
        }
    return inside ? static_cast<double>(grey) / static_cast<double>(inside) : 0.0;
}

// The grabs both Wayland provider tests make from a photo of the whole
// desktop `bgr`, each aimed at one window's middle: `notes` (shown in a
// native window) and `report` (in an Xwayland one), each window titled
// with its file's name, arrive as their files, byte for byte; "plain grey"
// as a snapshot without the field. The snapshot, for more
// checks (empty when it did not come).
inline cv::Mat expect_documents_and_a_snapshot(const std::string& url, const cv::Mat& bgr,
                                               const std::map<std::string, umf::provider::WindowInfo>& windows,
                                               const std::filesystem::path& notes,
                                               const std::filesystem::path& report,
                                               const std::filesystem::path& work) {
    // The window whose title names the file (some programs add their own
    // name to it).
    const auto rect_of = [&](const std::string& title) {
        for (const auto& [shown, window] : windows)
            if (shown.find(title) != std::string::npos) return window.rect;
        return umf::provider::WindowRect{};
    };
    for (const auto& [file, shot] : {std::pair{notes, "native"}, std::pair{report, "xwayland"}}) {
        const std::string title = file.filename().string();
        const auto got = requester_grab(url, photo_of_window(bgr, rect_of(title), work / (std::string(shot) + ".png")),
                                        work / ("got-" + std::string(shot)));
        EXPECT_EQ(got.value("kind", ""), "file") << got.dump();
        EXPECT_EQ(got.value("name", ""), title) << got.dump();
        EXPECT_NE(got.value("title", "").find(title), std::string::npos) << got.dump();
        EXPECT_EQ(read_file(got.value("saved", "")), read_file(file));
    }
    const auto shot = requester_grab(url, photo_of_window(bgr, rect_of("plain grey"), work / "plain.png"), work / "got-plain");
    EXPECT_EQ(shot.value("kind", ""), "snapshot") << shot.dump();
    EXPECT_EQ(shot.value("title", "").find("plain grey"), 0u) << shot.dump();
    const cv::Mat snapshot = cv::imread(shot.value("saved", ""), cv::IMREAD_COLOR);
    EXPECT_FALSE(snapshot.empty()) << "no snapshot saved";
    // Grey throughout below its title bar: the field was hidden for it.
    if (!snapshot.empty()) {
        EXPECT_GT(grey_share(snapshot), 0.95) << "the snapshot holds the field";
    }
    return snapshot;
}

// The field found in a photo of the whole desktop places its centre, the
// screen point (x, y), where the provider's placement puts it.
inline void expect_aim_at(const umf::Detection& detection, const umf::overlay::FieldPlacement& placement, double x,
                          double y) {
    double u = 0, v = 0;
    umf::overlay::screen_to_field(placement, x, y, u, v);
    EXPECT_NEAR(detection.aim_field.x(), u, 0.05);
    EXPECT_NEAR(detection.aim_field.y(), v, 0.05);
}

// The README's picture of a desktop (scripts/screenshots-wayland.sh): `bgr`
// at half size as `name` in $UMF_SCREENSHOT_DIR, when that is set.
inline void keep_screenshot(const cv::Mat& bgr, const std::string& name) {
    const char* keep = std::getenv("UMF_SCREENSHOT_DIR");
    if (!keep || !*keep) return;
    cv::Mat half;
    cv::resize(bgr, half, cv::Size(bgr.cols / 2, bgr.rows / 2), 0, 0, cv::INTER_AREA);
    cv::imwrite((std::filesystem::path(keep) / name).string(), half);
}

// After the desktop went away under a provider whose console is `log`: its
// keeper says it serves on without a desktop, at the same pairing URL, and
// its web page answers there.
inline void expect_serving_on_without_a_desktop(const std::filesystem::path& log, const std::string& url) {
    const std::string listening = url.substr(0, url.find('/', 8));
    ASSERT_TRUE(wait_until(
        [&] {
            const std::string text = read_file(log);
            const auto at = text.find("Serving on without a desktop");
            return at != std::string::npos && pairing_url_in(text.substr(at)) == url;
        },
        std::chrono::seconds(20)))
        << read_file(log);
    EXPECT_EQ(run_command("curl -s -k --max-time 10 -o /dev/null -w '%{http_code}' " + listening + "/").out, "200")
        << read_file(log);
}

}  // namespace umf::test
