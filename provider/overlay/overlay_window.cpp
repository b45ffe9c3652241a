#include "overlay/overlay_window.hpp"

#include <QGuiApplication>
#include <QPaintEvent>
#include <QPainter>
#include <QPainterPath>
#include <QRadialGradient>
#include <QScreen>
#include <QSurfaceFormat>
#include <algorithm>
#include <cmath>

#include "screen/board_window.hpp"

// Last: Xlib's macros (None, Bool) would clash with Qt's headers.
#include <X11/Xlib.h>

namespace umf::provider {

namespace {

// The soft edge of the focus circle: the field fades over the outer part of
// the radius, so the mask's edge does not read as a border to a detector.
constexpr double kFocusSoftness = 0.15;
// The pointer ring in logical pixels: the same apparent size on any screen.
constexpr double kRingRadius = 18.0;
constexpr double kTitlePointSize = 11.0;

// Qt's xcb plugin sends its requests when its event loop next sees an X
// event; a property change alone would wait in the buffer until then, and
// the pulse with it.
void flush_x11() {
    if (const auto* x11 = qGuiApp->nativeInterface<QNativeInterface::QX11Application>())
        if (Display* display = x11->display()) XFlush(display);
}

}  // namespace

OverlayWindow::OverlayWindow(QScreen* screen, ScreenField field, const std::vector<std::string>& palette) {
    QSurfaceFormat format;
    format.setAlphaBufferSize(8);  // an ARGB visual: the desktop shows through where there is no field
    setFormat(format);
    // Override-redirect (X11BypassWindowManagerHint) rather than a managed
    // "above" window: a window manager would frame, place, constrain,
    // possibly focus it and keep fullscreen windows above it, and some do
    // not copy _NET_WM_WINDOW_OPACITY to their frames, which would stop the
    // pulse. Unmanaged, the compositor reads the opacity from this window
    // itself. The price: restacking by the window manager can put windows
    // above it, which the overlay manager answers by raising it again.
    setFlags(Qt::FramelessWindowHint | Qt::WindowStaysOnTopHint | Qt::WindowTransparentForInput |
             Qt::WindowDoesNotAcceptFocus | Qt::Tool | Qt::X11BypassWindowManagerHint);
    setTitle("umf overlay");
    if (screen) setScreen(screen);
    cover_screen();
    set_field(std::move(field), palette);
}

void OverlayWindow::cover_screen() {
    if (screen()) setGeometry(screen()->geometry());
}

void OverlayWindow::set_field(ScreenField field, const std::vector<std::string>& palette) {
    field_ = std::move(field);
    layer_ = field_layer(field_, palette);
    update();
}

void OverlayWindow::set_opacity(double opacity) {
    setOpacity(std::clamp(opacity, 0.0, 1.0));
    flush_x11();
}

QRect OverlayWindow::logical_bounds(QPointF centre_px, double radius_px, double margin_px) const {
    const double dpr = devicePixelRatio();
    const double r = (radius_px + margin_px) / dpr;
    const QPointF c = centre_px / dpr;
    return QRectF(c.x() - r, c.y() - r, 2 * r, 2 * r).toAlignedRect().adjusted(-1, -1, 1, 1);
}

QRect OverlayWindow::pointer_bounds() const {
    if (!pointer_) return {};
    const QPointF c = *pointer_ / devicePixelRatio();
    QFont font;
    font.setPointSizeF(kTitlePointSize);
    const QRect text = QFontMetrics(font).boundingRect(pointer_title_);
    const QRectF ring(c.x() - kRingRadius - 3, c.y() - kRingRadius - 3, 2 * kRingRadius + 6, 2 * kRingRadius + 6);
    const QRectF label(c.x() + kRingRadius + 4, c.y() - text.height(), text.width() + 8, 2 * text.height());
    return ring.united(label).toAlignedRect().adjusted(-2, -2, 2, 2);
}

void OverlayWindow::set_focus(std::optional<QPointF> centre_px, double radius_px) {
    if (centre_px == focus_centre_ && radius_px == focus_radius_) return;
    // Going from all to part of the field or back changes the whole window;
    // a moving circle only the places it leaves and enters.
    if (!centre_px || !focus_centre_) {
        update();
    } else {
        update(logical_bounds(*focus_centre_, focus_radius_, 0));
        update(logical_bounds(*centre_px, radius_px, 0));
    }
    focus_centre_ = centre_px;
    focus_radius_ = std::max(0.0, radius_px);
}

void OverlayWindow::set_pointer(std::optional<QPointF> point_px, QString title) {
    if (point_px == pointer_ && title == pointer_title_) return;
    if (pointer_) update(pointer_bounds());
    pointer_ = point_px;
    pointer_title_ = std::move(title);
    if (pointer_) update(pointer_bounds());
}

void OverlayWindow::paintEvent(QPaintEvent* event) {
    ++paint_count_;
    const double dpr = devicePixelRatio();
    QPainter painter(this);
    painter.setClipRegion(event->region());
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.fillRect(event->rect(), Qt::transparent);
    // The layer is in physical pixels: tagged with the ratio it maps one to
    // one onto the backing store.
    layer_.setDevicePixelRatio(dpr);
    if (!focus_centre_) {
        painter.drawImage(QPointF(0, 0), layer_);
    } else if (focus_radius_ > 0) {
        const QRect bounds = logical_bounds(*focus_centre_, focus_radius_, 0);
        painter.save();
        painter.setClipRect(bounds, Qt::IntersectClip);
        painter.drawImage(QPointF(0, 0), layer_);
        const QPointF c = *focus_centre_ / dpr;
        const double r = focus_radius_ / dpr;
        QRadialGradient mask(c, r);
        mask.setColorAt(0.0, Qt::black);
        mask.setColorAt(1.0 - kFocusSoftness, Qt::black);
        mask.setColorAt(1.0, Qt::transparent);
        painter.setCompositionMode(QPainter::CompositionMode_DestinationIn);
        painter.fillRect(bounds, mask);
        painter.restore();
    }
    if (pointer_) {
        painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
        painter.setRenderHint(QPainter::Antialiasing);
        const QPointF c = *pointer_ / dpr;
        // White on a dark outline: legible on light and dark content alike.
        const QPen dark(QColor(0, 0, 0, 200), 4.0), light(Qt::white, 2.0);
        painter.setBrush(Qt::NoBrush);
        for (const QPen& pen : {dark, light}) {
            painter.setPen(pen);
            painter.drawEllipse(c, kRingRadius, kRingRadius);
        }
        if (!pointer_title_.isEmpty()) {
            QFont font;
            font.setPointSizeF(kTitlePointSize);
            QPainterPath text;
            text.addText(c + QPointF(kRingRadius + 8, QFontMetrics(font).ascent() / 2.0), font, pointer_title_);
            painter.strokePath(text, QPen(QColor(0, 0, 0, 220), 3.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
            painter.fillPath(text, Qt::white);
        }
    }
}

}  // namespace umf::provider
