// A libwayland-client connection of the backend's own (Qt's may be xcb
// through Xwayland, and has no layer shell anyway): the globals the field
// and the snapshots need, and the outputs with their names and places.
// Single-threaded: the field's runs on the Qt thread, each capture makes
// its own.
#pragma once

#include <wayland-client.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

struct zwlr_layer_shell_v1;
struct zwlr_screencopy_manager_v1;
struct zxdg_output_manager_v1;
struct zxdg_output_v1;

namespace umf::provider {

struct WaylandOutput {
    wl_output* output = nullptr;
    zxdg_output_v1* xdg_output = nullptr;
    std::uint32_t global = 0;
    std::string name;  // wl_output v4's or xdg_output's: the connector
    int x = 0, y = 0;  // layout position (xdg_output's logical one when known)
    int width = 0, height = 0;  // logical size when known, else the mode's pixels
    int scale = 1;
};

class WaylandConnection {
public:
    // `display` as WAYLAND_DISPLAY (a name in XDG_RUNTIME_DIR or a path);
    // empty: the environment's. Throws DesktopError when no compositor
    // answers within `timeout`.
    static std::unique_ptr<WaylandConnection> open(const std::string& display, std::chrono::milliseconds timeout);
    ~WaylandConnection();
    WaylandConnection(const WaylandConnection&) = delete;
    WaylandConnection& operator=(const WaylandConnection&) = delete;

    wl_display* display() const { return display_; }
    wl_compositor* compositor() const { return compositor_; }
    wl_shm* shm() const { return shm_; }
    zwlr_layer_shell_v1* layer_shell() const { return layer_shell_; }
    zwlr_screencopy_manager_v1* screencopy() const { return screencopy_; }
    // Whether the compositor offers wp_alpha_modifier_v1 (the pulse could
    // then be the compositor's; not used yet).
    bool offers_alpha_modifier() const { return alpha_modifier_; }
    const std::vector<std::unique_ptr<WaylandOutput>>& outputs() const { return outputs_; }

    // Sends, then dispatches until the compositor has answered everything
    // sent so far; false at the timeout or when the connection broke.
    bool roundtrip(std::chrono::milliseconds timeout);
    // Dispatches until `done` or the timeout; false at the timeout or when
    // the connection broke.
    bool dispatch_until(const std::function<bool()>& done, std::chrono::milliseconds timeout);

    // Called after an output came, went or changed (on dispatch).
    void set_outputs_changed(std::function<void()> changed) { outputs_changed_ = std::move(changed); }

private:
    WaylandConnection() = default;
    void on_global(wl_registry* registry, std::uint32_t name, const char* interface, std::uint32_t version);
    void on_global_remove(std::uint32_t name);
    void add_output(std::uint32_t global, std::uint32_t version);
    void watch_xdg_output(WaylandOutput& output);
    void outputs_changed();

    wl_display* display_ = nullptr;
    wl_registry* registry_ = nullptr;
    wl_compositor* compositor_ = nullptr;
    wl_shm* shm_ = nullptr;
    zwlr_layer_shell_v1* layer_shell_ = nullptr;
    zwlr_screencopy_manager_v1* screencopy_ = nullptr;
    zxdg_output_manager_v1* xdg_output_manager_ = nullptr;
    bool alpha_modifier_ = false;
    std::vector<std::unique_ptr<WaylandOutput>> outputs_;
    std::function<void()> outputs_changed_;

    friend struct WaylandOutputListeners;
};

}  // namespace umf::provider
