#include "provider/desktop/kde/wayland_outputs.hpp"

#include <poll.h>
#include <wayland-client.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>

#include "xdg-output-unstable-v1-client-protocol.h"

namespace umf::provider {

namespace {

struct Output {
    wl_output* output = nullptr;
    zxdg_output_v1* xdg = nullptr;
    DesktopOutput facts;
    int mode_width = 0, mode_height = 0;
    bool logical = false;  // xdg-output told the logical rectangle
};

struct Registry {
    WaylandFacts facts;
    zxdg_output_manager_v1* xdg_manager = nullptr;
    std::vector<std::unique_ptr<Output>> outputs;
};

void output_geometry(void* data, wl_output*, int32_t x, int32_t y, int32_t, int32_t, int32_t, const char*, const char*,
                     int32_t) {
    auto* o = static_cast<Output*>(data);
    if (!o->logical) {
        o->facts.rect.x = x;
        o->facts.rect.y = y;
    }
}
void output_mode(void* data, wl_output*, uint32_t flags, int32_t width, int32_t height, int32_t) {
    auto* o = static_cast<Output*>(data);
    if (flags & WL_OUTPUT_MODE_CURRENT) {
        o->mode_width = width;
        o->mode_height = height;
    }
}
void output_done(void*, wl_output*) {}
void output_scale(void* data, wl_output*, int32_t factor) { static_cast<Output*>(data)->facts.scale = factor; }
void output_name(void* data, wl_output*, const char* name) { static_cast<Output*>(data)->facts.name = name; }
void output_description(void*, wl_output*, const char*) {}
const wl_output_listener kOutputListener{output_geometry, output_mode,  output_done,
                                         output_scale,    output_name, output_description};

void xdg_position(void* data, zxdg_output_v1*, int32_t x, int32_t y) {
    auto* o = static_cast<Output*>(data);
    o->facts.rect.x = x;
    o->facts.rect.y = y;
    o->logical = true;
}
void xdg_size(void* data, zxdg_output_v1*, int32_t width, int32_t height) {
    auto* o = static_cast<Output*>(data);
    o->facts.rect.width = width;
    o->facts.rect.height = height;
    o->logical = true;
}
void xdg_done(void*, zxdg_output_v1*) {}
void xdg_name(void* data, zxdg_output_v1*, const char* name) {
    auto* o = static_cast<Output*>(data);
    if (o->facts.name.empty()) o->facts.name = name;
}
void xdg_description(void*, zxdg_output_v1*, const char*) {}
const zxdg_output_v1_listener kXdgListener{xdg_position, xdg_size, xdg_done, xdg_name, xdg_description};

void global(void* data, wl_registry* registry, uint32_t name, const char* interface, uint32_t version) {
    auto* r = static_cast<Registry*>(data);
    r->facts.globals.insert(interface);
    if (std::strcmp(interface, wl_output_interface.name) == 0) {
        auto output = std::make_unique<Output>();
        output->output = static_cast<wl_output*>(
            wl_registry_bind(registry, name, &wl_output_interface, std::min<uint32_t>(version, 4)));
        wl_output_add_listener(output->output, &kOutputListener, output.get());
        r->outputs.push_back(std::move(output));
    } else if (std::strcmp(interface, zxdg_output_manager_v1_interface.name) == 0) {
        r->xdg_manager = static_cast<zxdg_output_manager_v1*>(
            wl_registry_bind(registry, name, &zxdg_output_manager_v1_interface, std::min<uint32_t>(version, 3)));
    }
}
void global_remove(void*, wl_registry*, uint32_t) {}
const wl_registry_listener kRegistryListener{global, global_remove};

// A roundtrip that gives up at the deadline instead of blocking.
void roundtrip(wl_display* display, std::chrono::steady_clock::time_point deadline) {
    wl_callback* callback = wl_display_sync(display);
    bool done = false;
    static const wl_callback_listener listener{[](void* data, wl_callback*, uint32_t) { *static_cast<bool*>(data) = true; }};
    wl_callback_add_listener(callback, &listener, &done);
    while (!done) {
        while (wl_display_prepare_read(display) != 0) wl_display_dispatch_pending(display);
        wl_display_flush(display);
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
        pollfd pfd{wl_display_get_fd(display), POLLIN, 0};
        if (left <= 0 || ::poll(&pfd, 1, static_cast<int>(left)) <= 0) {
            wl_display_cancel_read(display);
            wl_callback_destroy(callback);
            throw DesktopError("KWin's Wayland display did not answer in time");
        }
        if (wl_display_read_events(display) != 0 || wl_display_dispatch_pending(display) < 0) {
            wl_callback_destroy(callback);
            throw DesktopError("KWin's Wayland connection broke (" + std::string(std::strerror(errno)) + ")");
        }
    }
    wl_callback_destroy(callback);
}

}  // namespace

WaylandFacts query_wayland(const std::string& display_name, std::chrono::milliseconds timeout) {
    wl_display* display = wl_display_connect(display_name.empty() ? nullptr : display_name.c_str());
    if (!display) throw DesktopError("cannot connect to the Wayland display '" + display_name + "'");
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    Registry r;
    wl_registry* registry = wl_display_get_registry(display);
    wl_registry_add_listener(registry, &kRegistryListener, &r);
    auto cleanup = [&] {
        for (auto& o : r.outputs) {
            if (o->xdg) zxdg_output_v1_destroy(o->xdg);
            wl_output_destroy(o->output);
        }
        if (r.xdg_manager) zxdg_output_manager_v1_destroy(r.xdg_manager);
        wl_registry_destroy(registry);
        wl_display_disconnect(display);
    };
    try {
        roundtrip(display, deadline);
        if (r.xdg_manager)
            for (auto& o : r.outputs) {
                o->xdg = zxdg_output_manager_v1_get_xdg_output(r.xdg_manager, o->output);
                zxdg_output_v1_add_listener(o->xdg, &kXdgListener, o.get());
            }
        roundtrip(display, deadline);
    } catch (...) {
        cleanup();
        throw;
    }
    for (auto& o : r.outputs) {
        DesktopOutput out = o->facts;
        if (o->logical && out.rect.width > 0 && o->mode_width > 0)
            out.scale = static_cast<double>(o->mode_width) / out.rect.width;  // fractional scales too
        if (!o->logical && out.scale > 0) {
            out.rect.width = static_cast<int>(std::lround(o->mode_width / out.scale));
            out.rect.height = static_cast<int>(std::lround(o->mode_height / out.scale));
        }
        if (!out.rect.empty()) r.facts.outputs.push_back(out);
    }
    WaylandFacts facts = std::move(r.facts);
    cleanup();
    return facts;
}

}  // namespace umf::provider
