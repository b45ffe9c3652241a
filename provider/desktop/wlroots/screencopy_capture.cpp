#include "provider/desktop/wlroots/screencopy_capture.hpp"

#include <QImage>
#include <cstring>
#include <memory>

#include "provider/desktop/wlroots/shm_buffer.hpp"
#include "provider/desktop/wlroots/wayland_connection.hpp"
#include "wlr-screencopy-unstable-v1-client-protocol.h"

namespace umf::provider {

namespace {

struct FrameState {
    std::uint32_t version = 1;
    bool have_shm = false;
    std::uint32_t format = 0;
    int width = 0, height = 0, stride = 0;
    bool buffers_listed = false;  // buffer_done (v3) or the buffer event (before)
    bool y_invert = false;
    bool ready = false;
    bool failed = false;
};

bool shm_format_supported(std::uint32_t f) {
    return f == WL_SHM_FORMAT_XRGB8888 || f == WL_SHM_FORMAT_ARGB8888 || f == WL_SHM_FORMAT_XBGR8888 ||
           f == WL_SHM_FORMAT_ABGR8888;
}

const zwlr_screencopy_frame_v1_listener kFrameListener = {
    // buffer: several may come; keep the first format we can read.
    [](void* data, zwlr_screencopy_frame_v1*, std::uint32_t format, std::uint32_t width, std::uint32_t height,
       std::uint32_t stride) {
        auto* s = static_cast<FrameState*>(data);
        if (!s->have_shm || (!shm_format_supported(s->format) && shm_format_supported(format))) {
            s->have_shm = true;
            s->format = format;
            s->width = static_cast<int>(width), s->height = static_cast<int>(height), s->stride = static_cast<int>(stride);
        }
        if (s->version < 3) s->buffers_listed = true;
    },
    [](void* data, zwlr_screencopy_frame_v1*, std::uint32_t flags) {
        static_cast<FrameState*>(data)->y_invert = (flags & ZWLR_SCREENCOPY_FRAME_V1_FLAGS_Y_INVERT) != 0;
    },
    [](void* data, zwlr_screencopy_frame_v1*, std::uint32_t, std::uint32_t, std::uint32_t) {
        static_cast<FrameState*>(data)->ready = true;
    },
    [](void* data, zwlr_screencopy_frame_v1*) {
        auto* s = static_cast<FrameState*>(data);
        s->failed = true;
        s->buffers_listed = true;
    },
    [](void*, zwlr_screencopy_frame_v1*, std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t) {},
    [](void*, zwlr_screencopy_frame_v1*, std::uint32_t, std::uint32_t, std::uint32_t) {},
    [](void* data, zwlr_screencopy_frame_v1*) { static_cast<FrameState*>(data)->buffers_listed = true; },
};

struct FrameGuard {
    zwlr_screencopy_frame_v1* frame;
    ~FrameGuard() { zwlr_screencopy_frame_v1_destroy(frame); }
};

}  // namespace

Capture capture_from_shm(const std::uint8_t* data, int width, int height, int stride, std::uint32_t format,
                         bool y_invert) {
    if (!shm_format_supported(format))
        throw DesktopError("the compositor offers screen pixels in a format this provider cannot read (" +
                           std::to_string(format) + ")");
    const bool swap = format == WL_SHM_FORMAT_XBGR8888 || format == WL_SHM_FORMAT_ABGR8888;
    Capture out{width, height, std::vector<std::uint32_t>(static_cast<std::size_t>(width) * height)};
    for (int y = 0; y < height; ++y) {
        const int source_row = y_invert ? height - 1 - y : y;
        const auto* in = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(source_row) * stride);
        std::uint32_t* row = &out.pixels[static_cast<std::size_t>(y) * width];
        for (int x = 0; x < width; ++x) {
            const std::uint32_t p = in[x];
            row[x] = swap ? 0xff000000u | ((p & 0xffu) << 16) | (p & 0xff00u) | ((p >> 16) & 0xffu) : 0xff000000u | p;
        }
    }
    return out;
}

Capture screencopy_region(const std::string& wayland_display, const std::string& output_name, const WindowRect& region,
                          std::chrono::milliseconds timeout) {
    if (region.empty()) return {};
    const auto connection = WaylandConnection::open(wayland_display, timeout);
    if (!connection->screencopy()) throw DesktopError("the compositor offers no screencopy: snapshots are off");
    const WaylandOutput* output = nullptr;
    for (const auto& o : connection->outputs())
        if (o->name == output_name) output = o.get();
    if (!output) throw DesktopError("the compositor names no output '" + output_name + "'");

    FrameState state;
    state.version = zwlr_screencopy_manager_v1_get_version(connection->screencopy());
    FrameGuard frame{zwlr_screencopy_manager_v1_capture_output_region(connection->screencopy(), 0, output->output, region.x,
                                                                      region.y, region.width, region.height)};
    zwlr_screencopy_frame_v1_add_listener(frame.frame, &kFrameListener, &state);
    if (!connection->dispatch_until([&] { return state.buffers_listed; }, timeout))
        throw DesktopError("the compositor did not describe the snapshot in time");
    if (state.failed) throw DesktopError("the compositor refused the snapshot");
    if (!state.have_shm) throw DesktopError("the compositor offers snapshots only in GPU buffers");
    const auto buffer = ShmBuffer::create(connection->shm(), state.width, state.height, state.stride, state.format);
    zwlr_screencopy_frame_v1_copy(frame.frame, buffer->buffer());
    if (!connection->dispatch_until([&] { return state.ready || state.failed; }, timeout))
        throw DesktopError("the compositor did not deliver the snapshot in time");
    if (state.failed) throw DesktopError("the compositor failed to copy the screen");
    Capture capture = capture_from_shm(buffer->data(), state.width, state.height, state.stride, state.format, state.y_invert);
    if (capture.width == region.width && capture.height == region.height) return capture;
    // A scaled output: its physical pixels brought to the layout's.
    QImage image(reinterpret_cast<const uchar*>(capture.pixels.data()), capture.width, capture.height,
                 capture.width * 4, QImage::Format_RGB32);
    const QImage scaled = image.scaled(region.width, region.height, Qt::IgnoreAspectRatio, Qt::SmoothTransformation)
                              .convertToFormat(QImage::Format_RGB32);
    Capture out{region.width, region.height, std::vector<std::uint32_t>(static_cast<std::size_t>(region.width) * region.height)};
    for (int y = 0; y < region.height; ++y)
        std::memcpy(&out.pixels[static_cast<std::size_t>(y) * region.width], scaled.constScanLine(y),
                    static_cast<std::size_t>(region.width) * 4);
    return out;
}

}  // namespace umf::provider
