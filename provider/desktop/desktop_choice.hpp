// Which desktop backend runs: chosen at start from the session's environment
// (XDG_SESSION_TYPE, WAYLAND_DISPLAY, DISPLAY, XDG_CURRENT_DESKTOP and the
// compositors' own sockets), or named with `--desktop`. Pure functions over
// the facts, so every case is tested without a session.
#pragma once

#include <optional>
#include <string>

namespace umf::provider {

enum class DesktopKind {
    headless,  // no display at all
    x11,       // an X server, with or without a window manager
    wlroots,   // Sway, Hyprland, river: layer shell, screencopy, the compositor's IPC
    kde,       // KDE Plasma (KWin)
    gnome,     // GNOME Shell (Mutter), through the umf Shell extension
    unsupported_wayland,  // a Wayland compositor with no backend (weston, ...)
};

// The environment as it bears on the choice.
struct DesktopFacts {
    std::string session_type;     // XDG_SESSION_TYPE
    std::string wayland_display;  // WAYLAND_DISPLAY
    std::string x_display;        // DISPLAY
    std::string current_desktop;  // XDG_CURRENT_DESKTOP, e.g. "ubuntu:GNOME", "KDE", "sway"
    std::string swaysock;         // SWAYSOCK
    std::string hyprland;         // HYPRLAND_INSTANCE_SIGNATURE
};

DesktopFacts desktop_facts_from_environment();

struct DesktopChoice {
    DesktopKind kind = DesktopKind::headless;
    // Why, in words for the console: "Wayland session (XDG_CURRENT_DESKTOP=sway)".
    std::string reason;
};

// `override_name` is --desktop's value: x11, wlroots, kde, gnome (or none,
// which is headless). Throws std::invalid_argument for another name.
DesktopChoice choose_desktop(const DesktopFacts& facts, const std::optional<std::string>& override_name = {});

// "x11", "wlroots", "kde", "gnome", "headless", "wayland (no backend)".
std::string to_string(DesktopKind kind);

// A Wayland session: Qt's X11 windows there go through Xwayland, which
// cannot make them click-through or translucent over native windows.
bool is_wayland(DesktopKind kind);

}  // namespace umf::provider
