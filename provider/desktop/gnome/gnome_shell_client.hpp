// The provider's side of org.umf.Shell1 (extension/org.umf.Shell1.xml): one
// private session-bus connection, typed calls, every call bounded by a
// timeout. QtDBus connections are thread-safe, so server threads and the Qt
// thread share one; blocking calls wait on the connection's own thread.
#pragma once

#include <QObject>
#include <QString>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

struct GnomeShellVersion {
    unsigned api = 0;
    std::string shell;  // "43.9"
};

// The field over one monitor as the extension shows it (FieldState()).
struct GnomeFieldState {
    int monitor = -1;
    bool visible = false;
    unsigned opacity = 0;  // 0..255
    bool focus = false;
    WindowRect rect;  // the actor's, desktop coordinates
    int image_width = 0, image_height = 0;
};

class GnomeShellClient {
public:
    // Connects to the session bus of DBUS_SESSION_BUS_ADDRESS. Throws
    // DesktopError when there is none.
    explicit GnomeShellClient(std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));
    ~GnomeShellClient();
    GnomeShellClient(const GnomeShellClient&) = delete;
    GnomeShellClient& operator=(const GnomeShellClient&) = delete;

    // Whether the extension holds its name on the bus (a quick question to
    // the bus itself).
    bool extension_present() const;
    // `changed(running)` each time the extension takes or gives up its name
    // (enabled, disabled, the shell restarted), on the calling thread's
    // event loop while the returned watcher lives.
    std::unique_ptr<QObject> watch_extension(std::function<void(bool running)> changed) const;

    // Each throws DesktopError: the extension is missing, refused or failed,
    // or did not answer in time.
    GnomeShellVersion version() const;
    std::vector<DesktopOutput> monitors() const;
    std::optional<WindowInfo> window_at(double x, double y, const WindowFilter& filter) const;
    std::vector<WindowInfo> windows() const;  // bottom to top
    bool move_window(unsigned long id, int x, int y) const;
    // The snapshot's file name in the private folder.
    std::string snapshot(const WindowRect& rect) const;
    // The same with the field in it, as a camera sees the screen.
    std::string screen_as_shown(const WindowRect& rect) const;
    void set_field(int monitor, const std::string& file_name) const;
    void drop_field(int monitor) const;
    std::vector<GnomeFieldState> field_state() const;

    // Sent without waiting for the reply: the pulse runs at up to 60 Hz on
    // the Qt thread. Errors are the extension's to log.
    void send_field_opacity(int monitor, double opacity) const;
    void send_field_focus(int monitor, std::optional<std::pair<double, double>> centre, double radius) const;
    void send_field_visible(int monitor, bool visible) const;
    // The aim mark's image (a file in the private folder; empty: the
    // one shown) with its top-left corner at (x, y), the monitor's physical
    // pixels.
    void send_aim_mark(int monitor, const std::string& file_name, double x, double y) const;
    void send_drop_aim_mark(int monitor) const;

private:
    std::string shot(const char* method, const WindowRect& rect) const;
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace umf::provider
