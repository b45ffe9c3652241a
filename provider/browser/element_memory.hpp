// What the page last said lay at an aimed point, kept for the next aims.
// An aim waits only tens of milliseconds for the page; a busy browser that
// answers later would make the phone's title flick from the link to the
// page while the hand has not moved. The page says where the element it
// found lies on the screen (its "screen_rect"), so a late answer at a point
// inside that rectangle, on the same tab showing the same address, can be
// given from memory for a few seconds. Grabs never are: they wait for the
// page itself.
#pragma once

#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "provider/browser/browser_windows.hpp"
#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// The element's "screen_rect" ([x, y, width, height] in screen pixels), or
// nullopt when it is missing, not four finite numbers, empty, or larger than
// any screen.
std::optional<WindowRect> element_screen_rect(const nlohmann::json& element);

class ElementMemory {
public:
    using Clock = std::chrono::steady_clock;
    explicit ElementMemory(std::chrono::milliseconds keep = std::chrono::milliseconds(3000)) : keep_(keep) {}

    // Keeps `element`, the page's answer for a point in `window`, when it
    // says where it lies; forgets what was kept otherwise.
    void remember(const BrowserMatch& window, const nlohmann::json& element, Clock::time_point now = Clock::now());
    // The kept element when it was said of the same window's same tab at the
    // same address, its rectangle holds (x, y), and it is not too old.
    std::optional<nlohmann::json> recall(const BrowserMatch& window, double x, double y,
                                         Clock::time_point now = Clock::now()) const;

private:
    struct Kept {
        int connection = 0;
        long window = -1, tab = -1;
        std::string url;
        WindowRect rect;
        Clock::time_point at;
        nlohmann::json element;
    };
    std::chrono::milliseconds keep_;
    mutable std::mutex mutex_;
    std::optional<Kept> kept_;
};

}  // namespace umf::provider
