// Hyprland's request socket: "j/clients" and "j/monitors" answer JSON and
// close. Hyprland cannot run here, so the parsing is apart and tested from
// written samples of its answers.
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// Where the instance's socket is: $XDG_RUNTIME_DIR/hypr/SIG/.socket.sock
// (Hyprland 0.40 on) when that exists, else /tmp/hypr/SIG/.socket.sock.
std::string hyprland_socket_path(const std::string& signature, const std::string& runtime_dir);

// The request's JSON; throws DesktopError as sway_request does.
nlohmann::json hyprland_request(const std::string& socket_path, const std::string& request,
                                std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));

// Active monitors; their width and height are physical pixels, the layout
// is in logical ones (divided by the scale).
std::vector<DesktopOutput> hyprland_outputs(const nlohmann::json& monitors);

// The mapped, not hidden clients on a monitor's active (or special)
// workspace, top-most first: fullscreen, then floating, then tiled, each by
// focus history (the most recently focused first). id is the client's
// address.
std::vector<WindowInfo> hyprland_visible_windows(const nlohmann::json& clients, const nlohmann::json& monitors);

}  // namespace umf::provider
