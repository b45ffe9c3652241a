// The desktop on a wlroots compositor (Sway, Hyprland, river): the field as
// a layer-shell surface (layer_field_surface.hpp), snapshots through
// wlr-screencopy, and, where the compositor has an IPC this speaks (Sway's
// i3-ipc, Hyprland's socket), the windows and the placement of new ones.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// Where the compositor is: the environment's, or a test's own.
struct WlrootsSockets {
    std::string wayland_display;     // WAYLAND_DISPLAY: a name in XDG_RUNTIME_DIR, or a path
    std::string swaysock;            // SWAYSOCK
    std::string hyprland_signature;  // HYPRLAND_INSTANCE_SIGNATURE
    std::string runtime_dir;         // XDG_RUNTIME_DIR
};
WlrootsSockets wlroots_sockets_from_environment();

class WlrootsDesktop final : public Desktop {
public:
    explicit WlrootsDesktop(WlrootsSockets sockets);

    std::string name() const override { return "wlroots"; }
    DesktopAbilities abilities() const override;
    // Sway's GET_OUTPUTS or Hyprland's monitors; without either, what the
    // Wayland connection tells. Empty when nothing answers.
    std::vector<DesktopOutput> outputs() const override;
    // The windows shown, top-most first. Throws DesktopError when the
    // compositor's IPC does not answer; empty without one.
    std::vector<WindowInfo> windows() const override;
    std::optional<WindowInfo> window_at(double x, double y, const WindowFilter& filter) const override;
    Capture capture(const WindowRect& rect) const override;
    std::unique_ptr<NewWindowWatch> watch_new_window(const WindowPlacement& where) const override;
    std::unique_ptr<FieldSurface> make_field_surface(QScreen* screen, ScreenField field,
                                                     const std::vector<std::string>& palette) override;

private:
    std::string hyprland_socket() const;

    WlrootsSockets sockets_;
};

// What the lead wires into the session's choice of backend.
std::unique_ptr<Desktop> make_wlroots_desktop(WlrootsSockets sockets = wlroots_sockets_from_environment());

}  // namespace umf::provider
