// For tests of the provider on a real X desktop: the pairing URL from its
// log, and the desktop captured until the field shows, as a photo both
// requesters can be given (BGR for the webcam requester's --image, and the
// detection on it).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "desktop/x11/x11_desktop.hpp"
#include "detect/detector.hpp"

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

// Captures `rect`'s width x height from the origin of `desktop` until
// `detector` finds the field in it (the overlay pulses, so one capture may
// fall on its faint phase) or `timeout` passes; the last capture either way.
inline DesktopPhoto capture_until_field(const umf::provider::X11Desktop& desktop, const umf::Detector& detector,
                                        int width, int height, std::chrono::milliseconds timeout) {
    DesktopPhoto photo;
    photo.bgr.create(height, width, CV_8UC3);
    std::vector<std::uint8_t> grey(static_cast<std::size_t>(width) * height);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        const umf::provider::Capture shot = desktop.capture({0, 0, width, height});
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

}  // namespace umf::test
