#include "provider/desktop/wlroots/wayland_connection.hpp"

#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "provider/desktop/desktop.hpp"
#include "wlr-layer-shell-unstable-v1-client-protocol.h"
#include "wlr-screencopy-unstable-v1-client-protocol.h"
#include "xdg-output-unstable-v1-client-protocol.h"

namespace umf::provider {

namespace {

using Clock = std::chrono::steady_clock;

// The highest versions this code speaks.
constexpr std::uint32_t kLayerShellVersion = 4;
constexpr std::uint32_t kScreencopyVersion = 3;
constexpr std::uint32_t kOutputVersion = 4;
constexpr std::uint32_t kXdgOutputVersion = 3;
constexpr std::uint32_t kCompositorVersion = 4;

template <class T>
T* bind(wl_registry* registry, std::uint32_t name, const wl_interface* interface, std::uint32_t offered,
        std::uint32_t wanted) {
    return static_cast<T*>(wl_registry_bind(registry, name, interface, std::min(offered, wanted)));
}

}  // namespace

struct WaylandOutputListeners {
    static void geometry(void* data, wl_output*, std::int32_t x, std::int32_t y, std::int32_t, std::int32_t,
                         std::int32_t, const char*, const char*, std::int32_t) {
        auto* o = static_cast<WaylandOutput*>(data);
        if (!o->xdg_output) o->x = x, o->y = y;
    }
    static void mode(void* data, wl_output*, std::uint32_t flags, std::int32_t width, std::int32_t height, std::int32_t) {
        auto* o = static_cast<WaylandOutput*>(data);
        if ((flags & WL_OUTPUT_MODE_CURRENT) && !o->xdg_output) o->width = width, o->height = height;
    }
    static void done(void*, wl_output*) {}
    static void scale(void* data, wl_output*, std::int32_t factor) { static_cast<WaylandOutput*>(data)->scale = factor; }
    static void name(void* data, wl_output*, const char* name) { static_cast<WaylandOutput*>(data)->name = name; }
    static void description(void*, wl_output*, const char*) {}

    static void xdg_position(void* data, zxdg_output_v1*, std::int32_t x, std::int32_t y) {
        auto* o = static_cast<WaylandOutput*>(data);
        o->x = x, o->y = y;
    }
    static void xdg_size(void* data, zxdg_output_v1*, std::int32_t width, std::int32_t height) {
        auto* o = static_cast<WaylandOutput*>(data);
        o->width = width, o->height = height;
    }
    static void xdg_done(void*, zxdg_output_v1*) {}
    static void xdg_name(void* data, zxdg_output_v1*, const char* name) {
        auto* o = static_cast<WaylandOutput*>(data);
        if (o->name.empty()) o->name = name;
    }
    static void xdg_description(void*, zxdg_output_v1*, const char*) {}

    static void global(void* data, wl_registry* registry, std::uint32_t name, const char* interface, std::uint32_t version) {
        static_cast<WaylandConnection*>(data)->on_global(registry, name, interface, version);
    }
    static void global_remove(void* data, wl_registry*, std::uint32_t name) {
        static_cast<WaylandConnection*>(data)->on_global_remove(name);
    }
};

namespace {

const wl_output_listener kOutputListener = {
    WaylandOutputListeners::geometry, WaylandOutputListeners::mode,  WaylandOutputListeners::done,
    WaylandOutputListeners::scale,    WaylandOutputListeners::name,  WaylandOutputListeners::description,
};
const zxdg_output_v1_listener kXdgOutputListener = {
    WaylandOutputListeners::xdg_position, WaylandOutputListeners::xdg_size, WaylandOutputListeners::xdg_done,
    WaylandOutputListeners::xdg_name,     WaylandOutputListeners::xdg_description,
};
const wl_registry_listener kRegistryListener = {WaylandOutputListeners::global, WaylandOutputListeners::global_remove};

}  // namespace

std::unique_ptr<WaylandConnection> WaylandConnection::open(const std::string& display, std::chrono::milliseconds timeout) {
    std::unique_ptr<WaylandConnection> c(new WaylandConnection);
    c->display_ = wl_display_connect(display.empty() ? nullptr : display.c_str());
    if (!c->display_)
        throw DesktopError("no Wayland compositor answers at '" + (display.empty() ? std::string("$WAYLAND_DISPLAY") : display) +
                           "': " + std::strerror(errno));
    c->registry_ = wl_display_get_registry(c->display_);
    wl_registry_add_listener(c->registry_, &kRegistryListener, c.get());
    // Globals, then what the outputs say of themselves.
    if (!c->roundtrip(timeout) || !c->roundtrip(timeout))
        throw DesktopError("the Wayland compositor did not answer in time");
    return c;
}

WaylandConnection::~WaylandConnection() {
    for (auto& o : outputs_) {
        if (o->xdg_output) zxdg_output_v1_destroy(o->xdg_output);
        if (wl_output_get_version(o->output) >= WL_OUTPUT_RELEASE_SINCE_VERSION) wl_output_release(o->output);
        else wl_output_destroy(o->output);
    }
    if (xdg_output_manager_) zxdg_output_manager_v1_destroy(xdg_output_manager_);
    if (layer_shell_) {
        if (zwlr_layer_shell_v1_get_version(layer_shell_) >= ZWLR_LAYER_SHELL_V1_DESTROY_SINCE_VERSION)
            zwlr_layer_shell_v1_destroy(layer_shell_);
        else
            wl_proxy_destroy(reinterpret_cast<wl_proxy*>(layer_shell_));
    }
    if (screencopy_) zwlr_screencopy_manager_v1_destroy(screencopy_);
    if (shm_) wl_shm_destroy(shm_);
    if (compositor_) wl_compositor_destroy(compositor_);
    if (registry_) wl_registry_destroy(registry_);
    if (display_) {
        wl_display_flush(display_);
        wl_display_disconnect(display_);
    }
}

void WaylandConnection::on_global(wl_registry* registry, std::uint32_t name, const char* interface,
                                  std::uint32_t version) {
    const std::string which = interface;
    if (which == wl_compositor_interface.name) {
        compositor_ = bind<wl_compositor>(registry, name, &wl_compositor_interface, version, kCompositorVersion);
    } else if (which == wl_shm_interface.name) {
        shm_ = bind<wl_shm>(registry, name, &wl_shm_interface, version, 1);
    } else if (which == zwlr_layer_shell_v1_interface.name) {
        layer_shell_ = bind<zwlr_layer_shell_v1>(registry, name, &zwlr_layer_shell_v1_interface, version, kLayerShellVersion);
    } else if (which == zwlr_screencopy_manager_v1_interface.name) {
        screencopy_ = bind<zwlr_screencopy_manager_v1>(registry, name, &zwlr_screencopy_manager_v1_interface, version,
                                                       kScreencopyVersion);
    } else if (which == zxdg_output_manager_v1_interface.name) {
        xdg_output_manager_ =
            bind<zxdg_output_manager_v1>(registry, name, &zxdg_output_manager_v1_interface, version, kXdgOutputVersion);
        for (auto& o : outputs_) watch_xdg_output(*o);
    } else if (which == wl_output_interface.name) {
        add_output(name, version);
    } else if (which == "wp_alpha_modifier_v1") {
        alpha_modifier_ = true;
    }
}

void WaylandConnection::add_output(std::uint32_t global, std::uint32_t version) {
    auto o = std::make_unique<WaylandOutput>();
    o->global = global;
    o->output = bind<wl_output>(registry_, global, &wl_output_interface, version, kOutputVersion);
    wl_output_add_listener(o->output, &kOutputListener, o.get());
    watch_xdg_output(*o);
    outputs_.push_back(std::move(o));
    outputs_changed();
}

void WaylandConnection::watch_xdg_output(WaylandOutput& o) {
    if (!xdg_output_manager_ || o.xdg_output) return;
    o.xdg_output = zxdg_output_manager_v1_get_xdg_output(xdg_output_manager_, o.output);
    zxdg_output_v1_add_listener(o.xdg_output, &kXdgOutputListener, &o);
}

void WaylandConnection::on_global_remove(std::uint32_t name) {
    const auto gone = std::find_if(outputs_.begin(), outputs_.end(), [&](const auto& o) { return o->global == name; });
    if (gone == outputs_.end()) return;
    if ((*gone)->xdg_output) zxdg_output_v1_destroy((*gone)->xdg_output);
    wl_output_destroy((*gone)->output);
    outputs_.erase(gone);
    outputs_changed();
}

void WaylandConnection::outputs_changed() {
    if (outputs_changed_) outputs_changed_();
}

bool WaylandConnection::dispatch_until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!done()) {
        if (wl_display_dispatch_pending(display_) < 0) return false;
        if (done()) return true;
        while (wl_display_prepare_read(display_) != 0)
            if (wl_display_dispatch_pending(display_) < 0) return false;
        if (wl_display_flush(display_) < 0 && errno != EAGAIN) {
            wl_display_cancel_read(display_);
            return false;
        }
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        pollfd p{wl_display_get_fd(display_), POLLIN, 0};
        if (left <= 0 || ::poll(&p, 1, static_cast<int>(left)) <= 0) {
            wl_display_cancel_read(display_);
            return false;
        }
        if (wl_display_read_events(display_) < 0) return false;
    }
    return true;
}

bool WaylandConnection::roundtrip(std::chrono::milliseconds timeout) {
    bool answered = false;
    wl_callback* callback = wl_display_sync(display_);
    static const wl_callback_listener listener = {
        [](void* data, wl_callback*, std::uint32_t) { *static_cast<bool*>(data) = true; }};
    wl_callback_add_listener(callback, &listener, &answered);
    const bool ok = dispatch_until([&] { return answered; }, timeout);
    wl_callback_destroy(callback);
    return ok;
}

}  // namespace umf::provider
