// The KDE Plasma (KWin, Wayland) backend of the desktop seam
// (desktop/desktop.hpp):
// - the window at a point: a KWin script lists the shown windows in
//   stacking order and answers over D-Bus (kwin_scripting.hpp); the pick
//   and the filter are done here (kwin_scripts.hpp);
// - snapshots: KWin's ScreenShot2 D-Bus interface (kwin_screenshot.hpp),
//   which needs umf-provider's .desktop file installed and KWin compositing
//   with OpenGL;
// - the field: a zwlr_layer_shell_v1 surface, which KWin offers since
//   Plasma 5.26; the surface itself is made by the caller's factory (the
//   wlroots backend's layer surface works unchanged here);
// - placement: a KWin script moves the put's new window.
// Works with KWin 5.27 and KWin 6 (the scripts speak both).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

using LayerSurfaceFactory = std::function<std::unique_ptr<FieldSurface>(
    const std::string& wayland_display, QScreen* screen, ScreenField field, const std::vector<std::string>& palette)>;

struct KdeDesktopOptions {
    std::string bus_address;      // empty: the session bus
    std::string wayland_display;  // empty: $WAYLAND_DISPLAY
    // Where the provider writes its KWin scripts; empty:
    // $XDG_RUNTIME_DIR/umf-kwin-PID. Made 0700, removed with the desktop.
    std::filesystem::path script_dir;
    // Every wait for KWin (a script's answer, a screenshot).
    std::chrono::milliseconds timeout{1000};
    // The field's surface; without one there is no field.
    LayerSurfaceFactory layer_surface;
};

// Throws DesktopError when KWin is not on the bus or its Wayland display
// cannot be reached.
std::unique_ptr<Desktop> make_kde_desktop(KdeDesktopOptions options = {});

}  // namespace umf::provider
