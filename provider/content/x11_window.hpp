// The X11 window under a screen point and the document it shows (docs/
// ARCHITECTURE.md, "Content", resolver 3). Windows come from the window
// manager's stacking list (EWMH), or the root's children without one; the
// document from the window's process (process_documents.hpp) or from the
// recently used files matched by the window's title (recent_files.hpp).
// Xlib stays out of this header: its macros (None, Status, Bool) clash with
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

#include "content/process_documents.hpp"
#include "content/recent_files.hpp"
#include "content/resolver.hpp"
#include "desktop/desktop.hpp"

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
class X11Desktop {
public:
    // An empty name means $DISPLAY. Throws std::runtime_error when the
    // display cannot be opened.
    explicit X11Desktop(const std::string& display_name = {});
    ~X11Desktop();
    X11Desktop(const X11Desktop&) = delete;
    X11Desktop& operator=(const X11Desktop&) = delete;

    // The root window: all screens of a multi-monitor desktop.
    WindowRect screen() const;
    // Whether a window manager with EWMH runs (its stacking list is used).
    bool has_ewmh() const;
    // Client windows that are shown (mapped, not minimised, not the desktop
    // background), top-most first.
    std::vector<WindowInfo> windows() const;
    // The top-most shown window containing the point that the filter does
    // not skip; nullopt on the bare desktop.
    std::optional<WindowInfo> window_at(double root_x, double root_y, const WindowFilter& filter = {}) const;
    // The screen's pixels in `rect`, clipped to the screen (empty outside).
    // Throws std::runtime_error when the server refuses or the visual is not
    // true colour.
    Capture capture(const WindowRect& rect) const;

private:
    struct Connection;
    std::unique_ptr<Connection> connection_;
    mutable std::mutex mutex_;
};


struct X11WindowOptions {
    WindowFilter filter;  // give own_pids at least getpid()
    ProcessDocumentOptions documents;
    std::filesystem::path recent_files = default_recent_files_path();  // empty: not consulted
};

// Kind file: the document of the window under the point. nullopt when the
// point is on no window or the window's document is unknown (the snapshot
// resolver answers then).
class X11WindowResolver final : public Resolver {
public:
    X11WindowResolver(std::shared_ptr<const X11Desktop> desktop, X11WindowOptions options = {});
    const char* name() const override { return "x11-window"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

    std::optional<WindowInfo> window_at(double root_x, double root_y) const;
    // The process's document when there is one, or the one of several the
    // title names; else the recently used file the title names.
    std::optional<std::filesystem::path> document_of(const WindowInfo& window) const;

private:
    std::shared_ptr<const X11Desktop> desktop_;
    X11WindowOptions options_;
    RecentFilesCache recent_files_;
};

}  // namespace umf::provider
