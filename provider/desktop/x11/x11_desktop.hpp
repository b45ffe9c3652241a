// The X11 backend of the desktop seam (desktop/desktop.hpp): windows come
// from the window manager's stacking list (EWMH), or the root's children
// without one; captures from the root window; the field in an override-
// redirect ARGB window per screen (overlay_window.hpp) mixed in by a
// compositing manager (compositor.hpp); a put's window placed through EWMH
// (desktop/x11/x11_window_watch.hpp). Xlib stays out of this header: its macros (None, Status, Bool) clash with
// Qt and the standard library.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

// Xlib's Display, without Xlib in every file that includes this one.
struct _XDisplay;

namespace umf::provider {

// Xlib's error handler is process-wide and its default exits the process
// (a window closed while it is looked at gives BadWindow). A connection of
// the provider's own is registered so that its errors are ignored, since
// each call's result tells of its failure; forget it before or as it closes.
void ignore_x11_errors(::_XDisplay* display);
void forget_x11_errors(::_XDisplay* display);
// The process the X server itself records for the client that made
// `window` (the X-Resource extension, local clients only), or 0 when it
// cannot say; unlike _NET_WM_PID, a client cannot claim another's.
int x_server_client_pid(::_XDisplay* display, unsigned long window);

// One connection to an X server, shared by the X11 resolvers; calls are
// serialised on it, so it is thread-safe.
class X11Desktop final : public Desktop {
public:
    // An empty name means $DISPLAY. Throws std::runtime_error when the
    // display cannot be opened.
    explicit X11Desktop(const std::string& display_name = {});
    ~X11Desktop() override;
    X11Desktop(const X11Desktop&) = delete;
    X11Desktop& operator=(const X11Desktop&) = delete;

    std::string name() const override { return "x11"; }
    // The field needs a compositing manager; placement a window manager.
    DesktopAbilities abilities() const override;
    // The root window as one output: all screens of a multi-monitor desktop
    // (the overlay follows the single screens through Qt).
    std::vector<DesktopOutput> outputs() const override;
    // Whether a window manager with EWMH runs (its stacking list is used).
    bool has_ewmh() const;
    // Client windows that are shown (mapped, not minimised, not the desktop
    // background), top-most first.
    std::vector<WindowInfo> windows() const override;
    // The top-most shown window containing the point that the filter does
    // not skip; nullopt on the bare desktop.
    std::optional<WindowInfo> window_at(double root_x, double root_y, const WindowFilter& filter) const override;
    std::optional<WindowInfo> window_at(double root_x, double root_y) const { return window_at(root_x, root_y, {}); }
    // The screen's pixels in `rect`, clipped to the screen (empty outside).
    // Throws std::runtime_error when the server refuses or the visual is not
    // true colour.
    Capture capture(const WindowRect& rect) const override;
    std::unique_ptr<NewWindowWatch> watch_new_window(const WindowPlacement& where) const override;
    std::unique_ptr<FieldSurface> make_field_surface(QScreen* screen, ScreenField field,
                                                     const std::vector<std::string>& palette) override;

private:
    struct Connection;
    std::unique_ptr<Connection> connection_;
    std::string display_name_;
    mutable std::mutex mutex_;
};


}  // namespace umf::provider
