// The field over one output of a wlroots compositor: a wlr-layer-shell
// surface on the OVERLAY layer, anchored to all four edges, with no
// exclusive zone, no keyboard and an empty input region from its first
// commit, so every click goes through to the windows below. The pulse is in
// the pixels (field_pixels.hpp), drawn at most once per frame callback and
// only when its 8-bit step changed. The connection is its own, served on
// the Qt thread by a socket notifier.
#pragma once

#include <QPointer>
#include <QScreen>
#include <QSocketNotifier>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/wlroots/field_pixels.hpp"
#include "provider/desktop/wlroots/shm_buffer.hpp"
#include "provider/desktop/wlroots/wayland_connection.hpp"
#include "provider/screen/aim_mark.hpp"

struct zwlr_layer_surface_v1;

namespace umf::provider {

class LayerFieldSurface final : public FieldSurface {
public:
    // Throws DesktopError when the compositor does not answer or offers no
    // layer shell.
    static std::unique_ptr<LayerFieldSurface> create(const std::string& wayland_display, QScreen* screen,
                                                     ScreenField field, const std::vector<std::string>& palette);
    ~LayerFieldSurface() override;

    const ScreenField& screen_field() const override { return field_; }
    void set_field(ScreenField field, const std::vector<std::string>& palette) override;
    void cover_screen() override;
    void set_opacity(double opacity) override;
    double pulse_opacity() const override { return pulse_; }
    void set_focus(std::optional<QPointF> centre_px, double radius_px) override;
    void set_aim_mark(std::optional<QPointF> point_px, const QString& title) override;
    void show() override;
    void hide() override;
    bool is_visible() const override { return visible_; }

    // Buffers committed so far: tests tell from it that a step was drawn.
    int frames_committed() const { return frames_committed_; }
    // The output it is on; empty while none.
    std::string output_name() const;
    // Serves the connection now (tests without an event loop turning).
    void dispatch_pending();

private:
    LayerFieldSurface(std::unique_ptr<WaylandConnection> connection, QScreen* screen);
    struct Slot {
        std::unique_ptr<ShmBuffer> buffer;
        std::optional<WindowRect> content;  // where it may hold nonzero pixels
    };

    WaylandOutput* matching_output() const;
    void create_surface();
    void destroy_surface();
    void after_dispatch();
    void draw_if_due();
    Slot* free_slot();
    void flush();
    void broke(const std::string& why);

    static void on_configure(void* data, zwlr_layer_surface_v1*, std::uint32_t serial, std::uint32_t width,
                             std::uint32_t height);
    static void on_closed(void* data, zwlr_layer_surface_v1*);
    static void on_frame_done(void* data, wl_callback* callback, std::uint32_t);

    std::unique_ptr<WaylandConnection> connection_;
    std::unique_ptr<QSocketNotifier> notifier_;
    QPointer<QScreen> screen_;
    ScreenField field_;
    std::unique_ptr<PulsedField> pixels_;

    wl_surface* surface_ = nullptr;
    zwlr_layer_surface_v1* layer_surface_ = nullptr;
    wl_output* bound_output_ = nullptr;
    wl_callback* frame_callback_ = nullptr;
    bool configured_ = false;
    bool outputs_changed_ = false;
    bool broken_ = false;
    std::vector<Slot> ring_;

    bool visible_ = false;
    double pulse_ = 0.0;
    std::optional<QPointF> focus_centre_;
    double focus_radius_ = 0.0;
    FocusMask mask_;
    // The ring and title, drawn over the field at full strength.
    struct ShownAimMark {
        AimMark mark;  // at the buffer's physical pixels
        QPoint at;         // its top-left corner in the buffer
        QString title;
    };
    std::optional<ShownAimMark> aim_mark_;
    WindowRect aim_mark_box() const;
    void blend_aim_mark(ShmBuffer& buffer) const;
    // What is on screen, so an unchanged step draws nothing.
    int content_generation_ = 0;
    int shown_generation_ = -1;
    int shown_level_ = -1;
    std::optional<WindowRect> shown_box_;
    int frames_committed_ = 0;
};

}  // namespace umf::provider
