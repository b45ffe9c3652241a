// The field mixed into a live desktop: a click-through, never-focused,
// translucent window over one screen that shows the field layer. The pulse
// is the window's opacity (_NET_WM_WINDOW_OPACITY), applied by the
// compositor: changing it costs no repaint, which a full-screen ARGB window
// at 60 Hz could not afford. A repaint happens only when what is drawn
// changes: the layer, the focus circle or the pointer.
#pragma once

#include <QImage>
#include <QPointF>
#include <QRasterWindow>
#include <QString>
#include <optional>

#include "screen/screen_field.hpp"

class QScreen;

namespace umf::provider {

class OverlayWindow : public QRasterWindow {
public:
    // `field` is the screen's field at its physical pixel size; `palette` as
    // in overlay::Preset.
    OverlayWindow(QScreen* screen, ScreenField field, const std::vector<std::string>& palette);

    const ScreenField& screen_field() const { return field_; }
    // A new field or palette, e.g. after the screen changed size or DPI.
    void set_field(ScreenField field, const std::vector<std::string>& palette);
    // Follows the screen's geometry (it may have moved or been resized).
    void cover_screen();

    // 0..1, the compositor's opacity for the whole window; no repaint.
    void set_opacity(double opacity);
    // Only the field within `radius_px` of `centre_px` is shown; nullopt shows
    // all of it. Both in the screen's physical pixels, as the placement.
    void set_focus(std::optional<QPointF> centre_px, double radius_px);
    // A ring where the phone points and the requester's title beside it, in
    // physical pixels; nullopt removes it.
    void set_pointer(std::optional<QPointF> point_px, QString title);

    // Paint events handled since the window was made: tests use it to tell
    // that the pulse does not repaint.
    int paint_count() const { return paint_count_; }

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    // The window's (logical) rectangle a circle of the screen's physical
    // pixels touches, with room for a soft edge or the title.
    QRect logical_bounds(QPointF centre_px, double radius_px, double margin_px) const;
    QRect pointer_bounds() const;

    ScreenField field_;
    QImage layer_;
    std::optional<QPointF> focus_centre_;
    double focus_radius_ = 0.0;
    std::optional<QPointF> pointer_;
    QString pointer_title_;
    int paint_count_ = 0;
};

}  // namespace umf::provider
