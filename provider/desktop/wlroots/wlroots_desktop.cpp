#include "provider/desktop/wlroots/wlroots_desktop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>

#include "provider/desktop/wlroots/hyprland_ipc.hpp"
#include "provider/desktop/wlroots/layer_field_surface.hpp"
#include "provider/desktop/wlroots/screencopy_capture.hpp"
#include "provider/desktop/wlroots/sway_ipc.hpp"
#include "provider/desktop/wlroots/sway_new_window_watch.hpp"
#include "provider/desktop/wlroots/sway_tree.hpp"
#include "provider/desktop/wlroots/wayland_connection.hpp"

namespace umf::provider {

namespace {

constexpr std::chrono::milliseconds kProbeTimeout{2000};

std::string env(const char* name) {
    const char* value = std::getenv(name);
    return value ? value : "";
}

int overlap(const WindowRect& a, const WindowRect& b) {
    const int w = std::min(a.x + a.width, b.x + b.width) - std::max(a.x, b.x);
    const int h = std::min(a.y + a.height, b.y + b.height) - std::max(a.y, b.y);
    return w > 0 && h > 0 ? w * h : 0;
}

}  // namespace

WlrootsSockets wlroots_sockets_from_environment() {
    const std::string runtime_dir = env("XDG_RUNTIME_DIR");
    return {env("WAYLAND_DISPLAY"), live_swaysock(env("SWAYSOCK"), runtime_dir), env("HYPRLAND_INSTANCE_SIGNATURE"),
            runtime_dir};
}

std::unique_ptr<Desktop> make_wlroots_desktop(WlrootsSockets sockets) {
    return std::make_unique<WlrootsDesktop>(std::move(sockets));
}

WlrootsDesktop::WlrootsDesktop(WlrootsSockets sockets) : sockets_(std::move(sockets)) {}

std::string WlrootsDesktop::hyprland_socket() const {
    return sockets_.hyprland_signature.empty() ? std::string()
                                               : hyprland_socket_path(sockets_.hyprland_signature, sockets_.runtime_dir);
}

DesktopAbilities WlrootsDesktop::abilities() const {
    DesktopAbilities a;
    try {
        const auto connection = WaylandConnection::open(sockets_.wayland_display, kProbeTimeout);
        a.field = connection->layer_shell() && connection->shm();
        a.snapshots = connection->screencopy() != nullptr;
        if (!a.field) a.notes.push_back("the compositor offers no layer shell (zwlr_layer_shell_v1): the field cannot be shown");
        if (!a.snapshots)
            a.notes.push_back("the compositor offers no screencopy (zwlr_screencopy_manager_v1): snapshots are off");
    } catch (const DesktopError& e) {
        a.notes.push_back(std::string(e.what()) + ": the field and snapshots are off");
    }
    if (!sockets_.swaysock.empty()) {
        try {
            sway_request(sockets_.swaysock, SwayMessage::get_version);
            a.windows = a.placement = true;
        } catch (const DesktopError& e) {
            a.notes.push_back(std::string("sway's IPC does not answer (") + e.what() +
                              "): the window under the point and placing new windows are off");
        }
    } else if (!sockets_.hyprland_signature.empty()) {
        try {
            hyprland_request(hyprland_socket(), "j/monitors");
            a.windows = true;
            a.notes.push_back("on Hyprland new windows are not moved to the pointed place yet");
        } catch (const DesktopError& e) {
            a.notes.push_back(std::string("Hyprland's socket does not answer (") + e.what() +
                              "): the window under the point is off");
        }
    } else {
        a.notes.push_back(
            "no Sway or Hyprland IPC ($SWAYSOCK, $HYPRLAND_INSTANCE_SIGNATURE): the window under the point and placing "
            "new windows are off on this compositor");
    }
    return a;
}

std::vector<DesktopOutput> WlrootsDesktop::outputs() const {
    try {
        if (!sockets_.swaysock.empty()) return sway_outputs(sway_request(sockets_.swaysock, SwayMessage::get_outputs));
        if (!sockets_.hyprland_signature.empty()) return hyprland_outputs(hyprland_request(hyprland_socket(), "j/monitors"));
        std::vector<DesktopOutput> out;
        const auto connection = WaylandConnection::open(sockets_.wayland_display, kProbeTimeout);
        for (const auto& o : connection->outputs())
            out.push_back({o->name, {o->x, o->y, o->width, o->height}, static_cast<double>(o->scale)});
        return out;
    } catch (const DesktopError& e) {
        if (std::getenv("UMF_DEBUG")) std::cerr << "umf: outputs: " << e.what() << "\n";
        return {};
    }
}

std::vector<WindowInfo> WlrootsDesktop::windows() const {
    if (!sockets_.swaysock.empty()) return sway_visible_windows(sway_request(sockets_.swaysock, SwayMessage::get_tree));
    if (!sockets_.hyprland_signature.empty()) {
        const std::string socket = hyprland_socket();
        return hyprland_visible_windows(hyprland_request(socket, "j/clients"), hyprland_request(socket, "j/monitors"));
    }
    return {};
}

std::optional<WindowInfo> WlrootsDesktop::window_at(double x, double y, const WindowFilter& filter) const {
    try {
        return topmost_window_at(windows(), x, y, filter);
    } catch (const DesktopError& e) {
        if (std::getenv("UMF_DEBUG")) std::cerr << "umf: window_at: " << e.what() << "\n";
        return std::nullopt;
    }
}

Capture WlrootsDesktop::capture(const WindowRect& rect) const {
    const auto all = outputs();
    if (all.empty()) throw DesktopError("the compositor names no outputs to capture");
    // The output under the rect's centre, else the one it overlaps most.
    const double cx = rect.x + rect.width / 2.0, cy = rect.y + rect.height / 2.0;
    const DesktopOutput* output = nullptr;
    for (const auto& o : all)
        if (o.rect.contains(cx, cy)) output = &o;
    if (!output)
        output = &*std::max_element(all.begin(), all.end(),
                                    [&](const auto& a, const auto& b) { return overlap(a.rect, rect) < overlap(b.rect, rect); });
    const WindowRect& o = output->rect;
    const int x0 = std::max(rect.x, o.x), y0 = std::max(rect.y, o.y);
    const int x1 = std::min(rect.x + rect.width, o.x + o.width), y1 = std::min(rect.y + rect.height, o.y + o.height);
    if (x1 <= x0 || y1 <= y0) return {};
    return screencopy_region(sockets_.wayland_display, output->name, {x0 - o.x, y0 - o.y, x1 - x0, y1 - y0});
}

std::unique_ptr<NewWindowWatch> WlrootsDesktop::watch_new_window(const WindowPlacement& where) const {
    if (sockets_.swaysock.empty()) return nullptr;
    return SwayNewWindowWatch::create(sockets_.swaysock, where);
}

std::unique_ptr<FieldSurface> WlrootsDesktop::make_field_surface(QScreen* screen, ScreenField field,
                                                                 const std::vector<std::string>& palette) {
    try {
        return LayerFieldSurface::create(sockets_.wayland_display, screen, std::move(field), palette);
    } catch (const DesktopError& e) {
        std::cerr << "umf: " << e.what() << "\n";
        return nullptr;
    }
}

}  // namespace umf::provider
