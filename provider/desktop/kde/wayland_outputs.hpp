// What a short libwayland-client connection to KWin tells: the globals it
// offers (whether zwlr_layer_shell_v1 is there for the field) and the
// outputs in its layout, from wl_output (scale, and its name from version
// 4) and xdg-output (the logical place and size, the name on older
// compositors).
#pragma once

#include <chrono>
#include <set>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

struct WaylandFacts {
    std::set<std::string> globals;  // interface names
    std::vector<DesktopOutput> outputs;
};

// `display` is a WAYLAND_DISPLAY value (a name in XDG_RUNTIME_DIR or a
// path); empty means $WAYLAND_DISPLAY. Throws DesktopError when it cannot
// connect or the compositor does not answer within `timeout`.
WaylandFacts query_wayland(const std::string& display, std::chrono::milliseconds timeout);

}  // namespace umf::provider
