// What the overlay manager keeps per screen, and the geometry its focus
// circle and backdrop share: private to field_overlay/overlay_manager.cpp
// and overlay_backdrop.cpp, the two halves of OverlayManager.
#pragma once

#include <QImage>
#include <QPointF>
#include <QRect>
#include <QScreen>
#include <QString>
#include <memory>
#include <optional>

#include "provider/field_overlay/overlay_manager.hpp"
#include "shared/overlay/background_blur.hpp"

namespace umf::provider {

namespace overlay_detail {

inline QSize physical_size(const QScreen* screen) {
    const double dpr = screen->devicePixelRatio();
    return {qRound(screen->geometry().width() * dpr), qRound(screen->geometry().height() * dpr)};
}

// The rectangle of a screen's physical pixels a circle touches, grown by `extra`.
inline QRect circle_bounds(QPointF centre, double radius, double extra) {
    const double r = radius + extra;
    return QRectF(centre.x() - r, centre.y() - r, 2 * r, 2 * r).toAlignedRect();
}

// How far the blur reaches at full strength: three standard deviations of
// half a module. Grabbed around the area a backdrop is good for, so that
// its edge (mirrored by blur_background) does not show in the circle.
inline int blur_margin_px(double module_px) {
    return static_cast<int>(std::ceil(3.0 * overlay::blur_sigma_px(1.0, module_px))) + 2;
}

// The root window's pixels through X11, on the display Qt uses, opened at
// the first grab: the default grab on an X server. Null images when there is none.
OverlayManager::GrabFunction x11_grab_function();

}  // namespace overlay_detail

struct OverlayManager::Entry {
    QScreen* screen = nullptr;
    int index = 0;
    std::unique_ptr<FieldSurface> window;
    std::optional<QPointF> focus;
    // The ring where a requester points, made at the first aim here.
    std::unique_ptr<AimWindow> aim_window;
    bool pointing = false;
    qint64 pointed_ms = 0;
    // Where and what, for a surface that draws the ring itself (Wayland).
    QPointF pointed_px;
    QString pointed_title;
    // The backdrop under the focus circle (screen physical pixels): the raw
    // grab and where, the area its blur is good for, where the circle was.
    QImage raw;
    QRect raw_rect;
    QRect good_rect;
    QPointF grabbed_centre;
    qint64 grabbed_ms = 0;
    bool grab_failed = false;  // the last grab gave nothing: no retry before kBackdropMaxAgeMs
    bool grab_wanted = false;
    double blurred_strength = -1.0;  // what the window's backdrop was blurred with
    double blurred_module_px = -1.0;
};

}  // namespace umf::provider
