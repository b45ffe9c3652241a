#include "provider/desktop/wlroots/layer_field_surface.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>

#include "provider/screen/aim_mark.hpp"
#include "provider/screen/board_window.hpp"
#include "wlr-layer-shell-unstable-v1-client-protocol.h"

namespace umf::provider {

namespace {

constexpr std::chrono::milliseconds kSetupTimeout{3000};
// Two buffers alternate; a third lets a frame be drawn while the compositor
// still reads both others.
constexpr std::size_t kRingSize = 3;

WindowRect united(const WindowRect& a, const WindowRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const int x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
    const int x1 = std::max(a.x + a.width, b.x + b.width), y1 = std::max(a.y + a.height, b.y + b.height);
    return {x0, y0, x1 - x0, y1 - y0};
}


}  // namespace

std::unique_ptr<LayerFieldSurface> LayerFieldSurface::create(const std::string& wayland_display, QScreen* screen,
                                                             ScreenField field, const std::vector<std::string>& palette) {
    auto connection = WaylandConnection::open(wayland_display, kSetupTimeout);
    if (!connection->layer_shell())
        throw DesktopError("the compositor offers no layer shell (zwlr_layer_shell_v1): the field cannot be shown");
    if (!connection->compositor() || !connection->shm())
        throw DesktopError("the compositor offers no wl_compositor or wl_shm: the field cannot be shown");
    std::unique_ptr<LayerFieldSurface> surface(new LayerFieldSurface(std::move(connection), screen));
    surface->set_field(std::move(field), palette);
    return surface;
}

LayerFieldSurface::LayerFieldSurface(std::unique_ptr<WaylandConnection> connection, QScreen* screen)
    : connection_(std::move(connection)), screen_(screen) {
    connection_->set_outputs_changed([this] { outputs_changed_ = true; });
    outputs_changed_ = false;
    notifier_ = std::make_unique<QSocketNotifier>(wl_display_get_fd(connection_->display()), QSocketNotifier::Read);
    QObject::connect(notifier_.get(), &QSocketNotifier::activated, [this] {
        if (wl_display_dispatch(connection_->display()) < 0) {
            broke(std::strerror(errno));
            return;
        }
        after_dispatch();
    });
}

LayerFieldSurface::~LayerFieldSurface() {
    notifier_.reset();
    destroy_surface();
    flush();
}

void LayerFieldSurface::broke(const std::string& why) {
    if (broken_) return;
    broken_ = true;
    notifier_->setEnabled(false);
    std::cerr << "umf: the connection to the Wayland compositor broke (" << why << "): the field is off\n";
}

void LayerFieldSurface::dispatch_pending() {
    if (broken_) return;
    if (wl_display_dispatch_pending(connection_->display()) < 0) return broke(std::strerror(errno));
    after_dispatch();
}

void LayerFieldSurface::after_dispatch() {
    if (outputs_changed_) {
        outputs_changed_ = false;
        cover_screen();
    }
    draw_if_due();
    flush();
}

void LayerFieldSurface::flush() {
    // EAGAIN: the socket is full; the rest goes with the next flush.
    if (!broken_ && wl_display_flush(connection_->display()) < 0 && errno != EAGAIN) broke(std::strerror(errno));
}

std::string LayerFieldSurface::output_name() const {
    for (const auto& o : connection_->outputs())
        if (o->output == bound_output_) return o->name;
    return {};
}

WaylandOutput* LayerFieldSurface::matching_output() const {
    const auto& outputs = connection_->outputs();
    if (outputs.empty()) return nullptr;
    if (screen_) {
        // Qt's wayland plugin and Xwayland both name screens after the
        // compositor's outputs; Qt on another platform has at least the place.
        const std::string name = screen_->name().toStdString();
        for (const auto& o : outputs)
            if (!name.empty() && o->name == name) return o.get();
        const QPoint at = screen_->geometry().topLeft();
        for (const auto& o : outputs)
            if (o->x == at.x() && o->y == at.y() && outputs.size() > 1) return o.get();
    }
    return outputs.front().get();
}

void LayerFieldSurface::create_surface() {
    WaylandOutput* output = matching_output();
    if (!output || broken_) return;
    bound_output_ = output->output;
    surface_ = wl_compositor_create_surface(connection_->compositor());
    // Click-through from the first frame: an empty input region.
    wl_region* nothing = wl_compositor_create_region(connection_->compositor());
    wl_surface_set_input_region(surface_, nothing);
    wl_region_destroy(nothing);
    layer_surface_ = zwlr_layer_shell_v1_get_layer_surface(connection_->layer_shell(), surface_, bound_output_,
                                                            ZWLR_LAYER_SHELL_V1_LAYER_OVERLAY, "umf-field");
    static const zwlr_layer_surface_v1_listener listener = {&LayerFieldSurface::on_configure, &LayerFieldSurface::on_closed};
    zwlr_layer_surface_v1_add_listener(layer_surface_, &listener, this);
    zwlr_layer_surface_v1_set_anchor(layer_surface_,
                                     ZWLR_LAYER_SURFACE_V1_ANCHOR_TOP | ZWLR_LAYER_SURFACE_V1_ANCHOR_BOTTOM |
                                         ZWLR_LAYER_SURFACE_V1_ANCHOR_LEFT | ZWLR_LAYER_SURFACE_V1_ANCHOR_RIGHT);
    zwlr_layer_surface_v1_set_size(layer_surface_, 0, 0);
    zwlr_layer_surface_v1_set_exclusive_zone(layer_surface_, -1);
    zwlr_layer_surface_v1_set_keyboard_interactivity(layer_surface_, ZWLR_LAYER_SURFACE_V1_KEYBOARD_INTERACTIVITY_NONE);
    wl_surface_commit(surface_);
    configured_ = false;
    shown_generation_ = -1;
    shown_box_.reset();
    flush();
}

void LayerFieldSurface::destroy_surface() {
    if (frame_callback_) wl_callback_destroy(frame_callback_);
    frame_callback_ = nullptr;
    if (layer_surface_) zwlr_layer_surface_v1_destroy(layer_surface_);
    if (surface_) wl_surface_destroy(surface_);
    layer_surface_ = nullptr;
    surface_ = nullptr;
    bound_output_ = nullptr;
    configured_ = false;
    // The compositor lets go of a destroyed surface's buffers without saying.
    ring_.clear();
    shown_box_.reset();
    shown_generation_ = -1;
}

void LayerFieldSurface::on_configure(void* data, zwlr_layer_surface_v1* layer, std::uint32_t serial, std::uint32_t,
                                     std::uint32_t) {
    auto* self = static_cast<LayerFieldSurface*>(data);
    zwlr_layer_surface_v1_ack_configure(layer, serial);
    if (!self->configured_) self->shown_generation_ = -1;
    self->configured_ = true;
    self->draw_if_due();
}

void LayerFieldSurface::on_closed(void* data, zwlr_layer_surface_v1*) {
    // The output went (or the compositor chose so): made again when the
    // outputs next change.
    static_cast<LayerFieldSurface*>(data)->destroy_surface();
}

void LayerFieldSurface::on_frame_done(void* data, wl_callback* callback, std::uint32_t) {
    auto* self = static_cast<LayerFieldSurface*>(data);
    wl_callback_destroy(callback);
    if (self->frame_callback_ == callback) self->frame_callback_ = nullptr;
    self->draw_if_due();
}

LayerFieldSurface::Slot* LayerFieldSurface::free_slot() {
    const int width = pixels_->width(), height = pixels_->height();
    for (auto& slot : ring_)
        if (!slot.buffer->busy()) {
            if (slot.buffer->width() == width && slot.buffer->height() == height) return &slot;
            slot = {ShmBuffer::create(connection_->shm(), width, height, width * 4, WL_SHM_FORMAT_ARGB8888), {}};
            return &slot;
        }
    if (ring_.size() >= kRingSize) return nullptr;
    ring_.push_back({ShmBuffer::create(connection_->shm(), width, height, width * 4, WL_SHM_FORMAT_ARGB8888), {}});
    // Fresh memory is zero: transparent everywhere.
    return &ring_.back();
}

void LayerFieldSurface::draw_if_due() {
    if (!visible_ || !configured_ || !surface_ || frame_callback_ || broken_ || !pixels_) return;
    if (pixels_->width() <= 0 || pixels_->height() <= 0) return;
    const int level = opacity_level(pulse_);
    if (level == shown_level_ && shown_generation_ == content_generation_) return;
    Slot* slot = nullptr;
    try {
        slot = free_slot();
    } catch (const DesktopError& e) {
        return broke(e.what());
    }
    if (!slot) return;  // all held by the compositor: drawn on a release
    ShmBuffer& buffer = *slot->buffer;
    const bool focused = focus_centre_.has_value();
    const WindowRect mark = aim_mark_box();
    const WindowRect box = united(focused ? mask_.box : pixels_->field_box(), mark);
    if (slot->content && !(*slot->content == box)) {
        const WindowRect& old = *slot->content;
        for (int y = old.y; y < old.y + old.height; ++y)
            std::memset(buffer.row(y) + old.x, 0, static_cast<std::size_t>(old.width) * 4);
    }
    // The ring's place from the last frame is cleared before the field is
    // painted again, or blending would pile up where the field is not.
    for (int y = mark.y; y < mark.y + mark.height; ++y)
        std::memset(buffer.row(y) + mark.x, 0, static_cast<std::size_t>(mark.width) * 4);
    if (focused) {
        if (!mask_.box.empty()) pixels_->paint_focus(buffer.data(), buffer.stride(), level, mask_);
    } else {
        pixels_->paint(buffer.data(), buffer.stride(), level);
    }
    blend_aim_mark(buffer);
    slot->content = box;

    // The buffer is the field's physical pixels; the surface is logical.
    int scale = 1;
    for (const auto& o : connection_->outputs())
        if (o->output == bound_output_) scale = std::max(1, o->scale);
    if (pixels_->width() % scale != 0 || pixels_->height() % scale != 0) scale = 1;
    wl_surface_set_buffer_scale(surface_, scale);
    wl_surface_attach(surface_, buffer.buffer(), 0, 0);
    buffer.mark_busy();
    const WindowRect damage = shown_generation_ < 0 ? WindowRect{0, 0, buffer.width(), buffer.height()}
                                                    : united(box, shown_box_.value_or(WindowRect{}));
    if (!damage.empty()) wl_surface_damage_buffer(surface_, damage.x, damage.y, damage.width, damage.height);
    frame_callback_ = wl_surface_frame(surface_);
    static const wl_callback_listener frame_listener = {&LayerFieldSurface::on_frame_done};
    wl_callback_add_listener(frame_callback_, &frame_listener, this);
    wl_surface_commit(surface_);
    ++frames_committed_;
    shown_level_ = level;
    shown_generation_ = content_generation_;
    shown_box_ = box;
    flush();
}

WindowRect LayerFieldSurface::aim_mark_box() const {
    if (!aim_mark_ || !pixels_) return {};
    const int x0 = std::max(0, aim_mark_->at.x()), y0 = std::max(0, aim_mark_->at.y());
    const int x1 = std::min(pixels_->width(), aim_mark_->at.x() + aim_mark_->mark.image.width());
    const int y1 = std::min(pixels_->height(), aim_mark_->at.y() + aim_mark_->mark.image.height());
    return x1 > x0 && y1 > y0 ? WindowRect{x0, y0, x1 - x0, y1 - y0} : WindowRect{};
}

void LayerFieldSurface::blend_aim_mark(ShmBuffer& buffer) const {
    const WindowRect box = aim_mark_box();
    for (int y = box.y; y < box.y + box.height; ++y) {
        const auto* src = reinterpret_cast<const QRgb*>(aim_mark_->mark.image.constScanLine(y - aim_mark_->at.y())) +
                          (box.x - aim_mark_->at.x());
        std::uint32_t* dst = buffer.row(y) + box.x;
        for (int x = 0; x < box.width; ++x) {
            // Both premultiplied ARGB: source over destination.
            const std::uint32_t s = src[x], keep = 255 - qAlpha(s);
            if (keep == 255) continue;
            const std::uint32_t d = dst[x];
            const auto channel = [&](int shift) {
                return (((s >> shift) & 255) + (((d >> shift) & 255) * keep + 127) / 255) << shift;
            };
            dst[x] = channel(24) | channel(16) | channel(8) | channel(0);
        }
    }
}

void LayerFieldSurface::set_aim_mark(std::optional<QPointF> point_px, const QString& title) {
    if (!point_px) {
        if (!aim_mark_) return;
        aim_mark_.reset();
    } else {
        // The mark is drawn again only for a new title; a move only shifts it.
        const bool new_mark = !aim_mark_ || aim_mark_->title != title;
        if (new_mark) aim_mark_ = ShownAimMark{aim_mark(title, 1.0), {}, title};
        const QPointF corner = *point_px - aim_mark_->mark.ring_centre;
        const QPoint at(static_cast<int>(std::lround(corner.x())), static_cast<int>(std::lround(corner.y())));
        if (!new_mark && at == aim_mark_->at) return;
        aim_mark_->at = at;
    }
    ++content_generation_;
    draw_if_due();
}

void LayerFieldSurface::set_field(ScreenField field, const std::vector<std::string>& palette) {
    field_ = std::move(field);
    pixels_ = std::make_unique<PulsedField>(field_layer(field_, palette));
    if (focus_centre_) mask_ = focus_mask(*focus_centre_, focus_radius_, pixels_->width(), pixels_->height());
    ++content_generation_;
    // Buffers of another size are made again as they come free; the drawn
    // content of the old field is gone with them.
    for (auto& slot : ring_) slot.content = WindowRect{0, 0, slot.buffer->width(), slot.buffer->height()};
    shown_generation_ = -1;
    draw_if_due();
}

void LayerFieldSurface::cover_screen() {
    if (!visible_ || broken_) return;
    WaylandOutput* wanted = matching_output();
    if (wanted && wanted->output == bound_output_ && surface_) return;
    destroy_surface();
    create_surface();
}

void LayerFieldSurface::set_opacity(double opacity) {
    pulse_ = std::clamp(opacity, 0.0, 1.0);
    draw_if_due();
}

void LayerFieldSurface::set_focus(std::optional<QPointF> centre_px, double radius_px) {
    radius_px = std::max(0.0, radius_px);
    if (centre_px == focus_centre_ && radius_px == focus_radius_) return;
    focus_centre_ = centre_px;
    focus_radius_ = radius_px;
    mask_ = centre_px ? focus_mask(*centre_px, radius_px, pixels_->width(), pixels_->height()) : FocusMask{};
    ++content_generation_;
    draw_if_due();
}

void LayerFieldSurface::show() {
    if (visible_) return;
    visible_ = true;
    if (!surface_) create_surface();
}

void LayerFieldSurface::hide() {
    if (!visible_) return;
    visible_ = false;
    destroy_surface();
    flush();
}

}  // namespace umf::provider
