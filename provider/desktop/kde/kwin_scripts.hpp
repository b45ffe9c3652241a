// The KWin scripts the KDE backend runs, and what their answers mean. Pure
// text in, text out: the JavaScript is made here and the JSON answers are
// read here, so both are tested without KWin. Each script answers once by
// calling umfAnswer(text), which the runner (kwin_scripting.hpp) defines as
// a callDBus back to the provider.
//
// The scripts speak both KWin 5.27 (workspace.clientList(), an integer
// currentDesktop and Window.desktop) and KWin 6 (workspace.windowList(),
// VirtualDesktop objects in currentDesktop and Window.desktops).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// One window as KWin's script API tells of it.
struct KWinWindow {
    std::string uuid;  // Window.internalId, stable for the window's life
    int stacking = 0;  // Window.stackingOrder: higher is above
    WindowRect rect;   // frameGeometry, rounded
    std::string caption;
    std::string resource_class;  // X11: WM_CLASS's class as KWin keeps it (lower case); Wayland: the app id
    std::string resource_name;   // X11: WM_CLASS's instance
    int pid = 0;
    bool x11 = false;  // an Xwayland window
    bool operator==(const KWinWindow&) const = default;
};

// `text` as a JavaScript string literal (quotes included), safe for any
// UTF-8 text.
std::string js_string(const std::string& text);

// The script that lists the shown windows (not minimised, normal windows and
// dialogs only, on the current virtual desktop), as a JSON array.
std::string list_windows_script();

// The script that gives window `uuid` the frame `rect`; answers "moved" or
// "missing".
std::string move_window_script(const std::string& uuid, const WindowRect& rect);

// The list script's answer; nullopt when it is not a JSON array of windows.
std::optional<std::vector<KWinWindow>> parse_window_list(const std::string& json);

// A stable id for the seam (WindowInfo::id) from KWin's uuid.
unsigned long window_id(const std::string& uuid);

// What the seam says of a window: the output is the one of `outputs` that
// holds most of it.
WindowInfo to_window_info(const KWinWindow& window, const std::vector<DesktopOutput>& outputs);

// The top-most window of `windows` (any order) containing the point that the
// filter does not skip.
std::optional<WindowInfo> window_at_point(const std::vector<KWinWindow>& windows, double x, double y,
                                          const WindowFilter& filter, const std::vector<DesktopOutput>& outputs);

}  // namespace umf::provider
