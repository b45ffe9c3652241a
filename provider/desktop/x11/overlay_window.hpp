// The field mixed into a live desktop: a click-through, never-focused,
// translucent window over one screen that shows the field layer. The pulse
// is the window's opacity (_NET_WM_WINDOW_OPACITY), applied by the
// compositor: changing it costs no repaint, which a full-screen ARGB window
// at 60 Hz could not afford. A repaint happens only when what is drawn
// changes: the layer or the focus circle. The aim ring has a window of
// its own (aim_window.hpp).
//
// One exception, the painted pulse (the manager's choice for Region::focus
// with a preset's blur): the window is given the screen under the focus
// circle, grabbed without the overlay and blurred (the backdrop), and draws
// inside the circle an opaque mix (1 - a) * backdrop + a * module colour, a
// being the pulse opacity. The window's own opacity then stays 1 and each
// visible step of the pulse repaints the circle's bounding rectangle only.
// Outside the circle the window stays transparent; at its soft edge the mix
// fades to transparent, so the real desktop shows through. Where the circle
// has moved off the backdrop (before the next grab) the field is painted
// translucent at opacity a over the real desktop, as the compositor would.
#pragma once

#include <QImage>
#include <QPointF>
#include <QRasterWindow>
#include <QString>
#include <cstdint>
#include <optional>
#include <vector>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/x11/x11_stacking.hpp"
#include "provider/screen/screen_field.hpp"

class QPainter;
class QScreen;

namespace umf::provider {

class OverlayWindow final : public QRasterWindow, public FieldSurface {
public:
    // `field` is the screen's field at its physical pixel size; `palette` as
    // in overlay::Preset.
    OverlayWindow(QScreen* screen, ScreenField field, const std::vector<std::string>& palette);

    const ScreenField& screen_field() const override { return field_; }
    // A new field or palette, e.g. after the screen changed size or DPI.
    void set_field(ScreenField field, const std::vector<std::string>& palette) override;
    // Follows the screen's geometry (it may have moved or been resized).
    void cover_screen() override;

    // 0..1, the pulse: the compositor's opacity for the whole window, no
    // repaint; with the painted pulse a repaint of the focus circle instead.
    // A pulse above pixel_opacity() raises it (a repaint).
    void set_opacity(double opacity) override;
    // The most the pulse reaches (the preset's opacity_max). The field's own
    // pixels carry it as their alpha (premultiplied) and the window's opacity
    // property is only the pulse's share of it, so a compositor that ignores
    // _NET_WM_WINDOW_OPACITY still shows a translucent field, never an opaque
    // one that hides the desktop.
    void set_pixel_opacity(double ceiling) override;
    double pixel_opacity() const { return pixel_opacity_; }
    // The pulse as last given to set_opacity.
    double pulse_opacity() const override { return pulse_; }

    // The painted pulse (see the top of the file): on, the window's opacity is
    // 1 and set_opacity repaints the circle; off (the default), the backdrop
    // is dropped and the compositor's opacity pulses again.
    bool supports_painted_pulse() const override { return true; }
    void set_painted_pulse(bool on) override;
    bool painted_pulse() const { return painted_pulse_; }
    // The blurred screen content at `origin_px` (the screen's physical
    // pixels), any format (kept as RGB32); a null image drops it. Used only
    // with the painted pulse.
    void set_backdrop(QImage blurred, QPoint origin_px) override;
    // The screen's physical pixels the backdrop covers (empty without one).
    QRect backdrop_rect() const { return backdrop_.isNull() ? QRect() : QRect(backdrop_origin_, backdrop_.size()); }
    // Only the field within `radius_px` of `centre_px` is shown; nullopt shows
    // all of it. Both in the screen's physical pixels, as the placement.
    void set_focus(std::optional<QPointF> centre_px, double radius_px) override;

    // FieldSurface's show, hide and raise are the window's.
    void show() override { QRasterWindow::show(); }
    void hide() override { QRasterWindow::hide(); }
    bool is_visible() const override { return isVisible(); }
    void raise() override { QRasterWindow::raise(); }
    void raise_under(const QWindow& sibling) override { stack_under(*this, sibling); }

    // Paint events handled since the window was made: tests use it to tell
    // that the pulse does not repaint.
    int paint_count() const { return paint_count_; }

    // What paintEvent draws within `region` (logical pixels), on a painter
    // over the window or, in tests, over an image of the window's size.
    void paint_to(QPainter& painter, const QRegion& region);

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    // The window's (logical) rectangle a circle of the screen's physical
    // pixels touches, with room for a soft edge or the title.
    QRect logical_bounds(QPointF centre_px, double radius_px, double margin_px) const;
    // The focus circle drawn as the painted pulse: the opaque mix over the
    // backdrop, the translucent field beyond it.
    void paint_painted_focus(QPainter& painter);

    ScreenField field_;
    QImage layer_;
    std::optional<QPointF> focus_centre_;
    double focus_radius_ = 0.0;
    int paint_count_ = 0;
    double pulse_ = 0.0;
    double pixel_opacity_ = 1.0;
    bool painted_pulse_ = false;
    // The window's opacity property for the pulse now.
    double window_opacity() const;
    // The input region emptied on the X server itself, before the window is
    // first mapped: no click lands on the field, from its first frame on.
    void empty_input_region();
    QImage backdrop_;  // Format_RGB32, physical pixels
    QPoint backdrop_origin_;
    // The painted circle's soft mask, kept while only the pulse moves.
    struct Mask {
        QRect box;  // physical pixels
        QPointF centre;
        double radius = -1.0;
        qint64 layer_key = 0;
        std::vector<std::uint8_t> alpha;
    };
    Mask mask_;
};

}  // namespace umf::provider
