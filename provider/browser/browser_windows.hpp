// What the browser companion tells the provider about a browser's windows,
// and which of them a desktop window is. Pure: no sockets, no desktop.
//
// The extension (browser/extension) reports, per normal (never private)
// window, its bounds on the screen and its active tab; the host adds the
// browser's process id. A window under the point (desktop/desktop.hpp) is
// matched to a reported one by that pid, its bounds and its title.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

struct BrowserTab {
    long id = -1;
    std::string url;    // empty unless http(s): nothing else leaves the machine
    std::string title;  // clipped, valid UTF-8
    double zoom = 1;
};

struct BrowserWindow {
    long id = -1;        // the extension's window id
    WindowRect bounds;   // screen pixels; empty where the browser cannot tell (Wayland)
    bool focused = false;
    BrowserTab tab;      // the active tab
};

// One connected browser: what its host and extension said.
struct BrowserState {
    int connection = 0;     // the link's id for it
    std::string name;       // "chromium", "firefox", ...
    std::string version;
    int pid = 0;            // the browser's process (the host's parent)
    std::vector<BrowserWindow> windows;
};

// Text from a browser as the phone may show it: valid UTF-8 of at most
// protocol::kMaxTitleBytes, control and bidirectional characters replaced.
std::string browser_text(const std::string& raw);

// Whether a URL may leave the machine: http or https, at most
// protocol::kMaxUrlBytes, no spaces or control characters.
bool is_shareable_url(const std::string& url);

// The windows of a "windows" message ({"type":"windows","windows":[...]}).
// Private windows (incognito: true) and their tabs are dropped, whatever
// else they say; URLs that may not leave are blanked; titles cleaned and
// clipped. Throws std::invalid_argument on a malformed message.
std::vector<BrowserWindow> parse_browser_windows(const nlohmann::json& message);

struct BrowserMatch {
    int connection = 0;  // the browser's, in the link
    BrowserWindow window;
};

// The reported window that is `window` (a desktop window of process
// window.pid), or nullopt. Bounds must overlap well and, where both have a
// title, the desktop's title must begin with the tab's; on Wayland (empty
// bounds) the title alone decides, and must be unique. `others` are the
// desktop's other windows: when one of them would match the same reported
// window, which of the two it is cannot be told (a private window, never
// reported, over a normal one showing the same page), and nothing matches.
std::optional<BrowserMatch> match_browser_window(const std::vector<BrowserState>& browsers, const WindowInfo& window,
                                                 const std::vector<WindowInfo>& others = {});

}  // namespace umf::provider
