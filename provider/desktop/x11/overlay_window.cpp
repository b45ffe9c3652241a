#include "provider/desktop/x11/overlay_window.hpp"

#include <QGuiApplication>
#include <QPaintEvent>
#include <QPainter>
#include <QPainterPath>
#include <QRadialGradient>
#include <QScreen>
#include <QSurfaceFormat>
#include <algorithm>
#include <cmath>

#include "provider/screen/board_window.hpp"

// Last: Xlib's macros (None, Bool) would clash with Qt's headers.
#include <X11/Xlib.h>
#include <X11/extensions/shape.h>

namespace umf::provider {

namespace {

// The soft edge of the focus circle: the field fades over the outer part of
// the radius, so the mask's edge does not read as a border to a detector.
constexpr double kFocusSoftness = 0.15;

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
    // Made now, not at the first show(): Qt's own empty input shape comes
    // with its platform window, and ours is set on the X server before any
    // map, whatever the Qt version does.
    create();
    if (QGuiApplication::platformName() == QLatin1String("xcb")) empty_input_region();
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
    opacity = std::clamp(opacity, 0.0, 1.0);
    if (painted_pulse_) {
        if (opacity != pulse_) {
            pulse_ = opacity;
            // The circle alone changes; without one (never so from the
            // manager) the whole field.
            if (focus_centre_) update(logical_bounds(*focus_centre_, focus_radius_, 0));
            else update();
        }
        return;
    }
    pulse_ = opacity;
    if (opacity > pixel_opacity_) return set_pixel_opacity(opacity);
    setOpacity(window_opacity());
    flush_x11();
}

double OverlayWindow::window_opacity() const {
    if (painted_pulse_) return 1.0;
    return pixel_opacity_ > 0 ? std::clamp(pulse_ / pixel_opacity_, 0.0, 1.0) : 0.0;
}

void OverlayWindow::set_pixel_opacity(double ceiling) {
    ceiling = std::clamp(ceiling, 0.0, 1.0);
    if (ceiling < pulse_) ceiling = pulse_;
    if (ceiling == pixel_opacity_) return;
    pixel_opacity_ = ceiling;
    setOpacity(window_opacity());
    flush_x11();
    update();
}

void OverlayWindow::empty_input_region() {
    const auto* x11 = qGuiApp->nativeInterface<QNativeInterface::QX11Application>();
    Display* display = x11 ? x11->display() : nullptr;
    if (!display) return;
    int event_base = 0, error_base = 0;
    if (!XShapeQueryExtension(display, &event_base, &error_base)) return;
    // No rectangles: an empty input shape, so the pointer goes to what is below.
    XShapeCombineRectangles(display, static_cast<::Window>(winId()), ShapeInput, 0, 0, nullptr, 0, ShapeSet,
                            Unsorted);
    XFlush(display);
}

void OverlayWindow::set_painted_pulse(bool on) {
    if (on == painted_pulse_) return;
    painted_pulse_ = on;
    if (!on) backdrop_ = QImage();
    setOpacity(window_opacity());
    flush_x11();
    update();
}

void OverlayWindow::set_backdrop(QImage blurred, QPoint origin_px) {
    if (!blurred.isNull() && blurred.format() != QImage::Format_RGB32)
        blurred = blurred.convertToFormat(QImage::Format_RGB32);
    const QRect before = backdrop_rect();
    backdrop_ = std::move(blurred);
    backdrop_origin_ = origin_px;
    if (!painted_pulse_ || !focus_centre_) return;
    // Only the circle can show it.
    const QRect changed = before.united(backdrop_rect());
    const double dpr = devicePixelRatio();
    const QRect circle = logical_bounds(*focus_centre_, focus_radius_, 0);
    update(circle.intersected(QRectF(QPointF(changed.topLeft()) / dpr, QSizeF(changed.size()) / dpr)
                                  .toAlignedRect()
                                  .adjusted(-1, -1, 1, 1)));
}

QRect OverlayWindow::logical_bounds(QPointF centre_px, double radius_px, double margin_px) const {
    const double dpr = devicePixelRatio();
    const double r = (radius_px + margin_px) / dpr;
    const QPointF c = centre_px / dpr;
    return QRectF(c.x() - r, c.y() - r, 2 * r, 2 * r).toAlignedRect().adjusted(-1, -1, 1, 1);
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

void OverlayWindow::paintEvent(QPaintEvent* event) {
    ++paint_count_;
    QPainter painter(this);
    paint_to(painter, event->region());
}

void OverlayWindow::paint_painted_focus(QPainter& painter) {
    const double dpr = devicePixelRatio();
    // The circle's pixels, physical, within the window and the layer.
    const QRect bounds = logical_bounds(*focus_centre_, focus_radius_, 0).intersected(QRect(QPoint(), size()));
    const QRect box = QRectF(QPointF(bounds.topLeft()) * dpr, QSizeF(bounds.size()) * dpr)
                          .toAlignedRect()
                          .intersected(layer_.rect());
    if (box.isEmpty()) return;
    // The mask, 0..255 a pixel: the soft circle where the layer holds the
    // field (as the gradient mask of the compositor's pulse: 1 inside,
    // falling linearly to 0 at the radius), 0 off it. Made again only when
    // the circle, the field or the ratio changed; a pulse step reuses it.
    if (mask_.box != box || mask_.centre != *focus_centre_ || mask_.radius != focus_radius_ ||
        mask_.layer_key != layer_.cacheKey()) {
        mask_ = {box, *focus_centre_, focus_radius_, layer_.cacheKey(), {}};
        mask_.alpha.resize(static_cast<std::size_t>(box.width()) * box.height());
        const double cx = focus_centre_->x(), cy = focus_centre_->y(), r = focus_radius_;
        const double inner = r * (1.0 - kFocusSoftness);
        for (int y = 0; y < box.height(); ++y) {
            const auto* field = reinterpret_cast<const QRgb*>(layer_.constScanLine(box.y() + y)) + box.x();
            const double dy = box.y() + y + 0.5 - cy;
            std::uint8_t* out = &mask_.alpha[static_cast<std::size_t>(y) * box.width()];
            for (int x = 0; x < box.width(); ++x) {
                const double dx = box.x() + x + 0.5 - cx;
                const double d = std::sqrt(dx * dx + dy * dy);
                const double m = qAlpha(field[x]) == 0 || d >= r ? 0.0 : d <= inner ? 1.0 : (r - d) / (r - inner);
                out[x] = static_cast<std::uint8_t>(std::lround(m * 255.0));
            }
        }
    }
    QImage out(box.size(), QImage::Format_ARGB32_Premultiplied);
    // The pulse in 1/65536: the mix is then exact to a rounding.
    const std::uint32_t a = static_cast<std::uint32_t>(std::lround(pulse_ * 65536.0));
    const std::uint32_t a8 = static_cast<std::uint32_t>(std::lround(pulse_ * 255.0));
    const QRect covered = backdrop_rect().intersected(box);
    for (int y = 0; y < out.height(); ++y) {
        const int sy = box.y() + y;
        const auto* field = reinterpret_cast<const QRgb*>(layer_.constScanLine(sy)) + box.x();
        const std::uint8_t* mask = &mask_.alpha[static_cast<std::size_t>(y) * box.width()];
        auto* row = reinterpret_cast<QRgb*>(out.scanLine(y));
        const bool backdrop_row = !covered.isEmpty() && sy >= covered.top() && sy <= covered.bottom();
        // x in the box where the backdrop starts and ends on this row.
        const int x0 = backdrop_row ? covered.left() - box.x() : out.width();
        const int x1 = backdrop_row ? covered.right() + 1 - box.x() : out.width();
        const QRgb* under = backdrop_row ? reinterpret_cast<const QRgb*>(backdrop_.constScanLine(sy - backdrop_origin_.y())) +
                                               (box.x() - backdrop_origin_.x())
                                         : nullptr;
        for (int x = 0; x < out.width(); ++x) {
            const std::uint32_t m = mask[x];
            if (m == 0) {
                row[x] = 0;
                continue;
            }
            const QRgb c = field[x];
            std::uint32_t red, green, blue, alpha;
            if (x >= x0 && x < x1) {
                // Opaque: the blurred content and the module mixed.
                const QRgb b = under[x];
                const auto mix = [a](std::uint32_t bv, std::uint32_t cv) { return (bv * (65536 - a) + cv * a + 32768) >> 16; };
                red = mix(qRed(b), qRed(c));
                green = mix(qGreen(b), qGreen(c));
                blue = mix(qBlue(b), qBlue(c));
                alpha = 255;
            } else {
                // Off the backdrop: the module at opacity a over the desktop.
                red = (qRed(c) * a8 + 127) / 255;
                green = (qGreen(c) * a8 + 127) / 255;
                blue = (qBlue(c) * a8 + 127) / 255;
                alpha = a8;
            }
            if (m != 255) {
                // Premultiplied by the soft edge.
                red = (red * m + 127) / 255;
                green = (green * m + 127) / 255;
                blue = (blue * m + 127) / 255;
                alpha = (alpha * m + 127) / 255;
            }
            row[x] = qRgba(static_cast<int>(red), static_cast<int>(green), static_cast<int>(blue), static_cast<int>(alpha));
        }
    }
    out.setDevicePixelRatio(dpr);
    painter.save();
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.drawImage(QPointF(box.topLeft()) / dpr, out);
    painter.restore();
}

void OverlayWindow::paint_to(QPainter& painter, const QRegion& region) {
    const double dpr = devicePixelRatio();
    painter.setClipRegion(region);
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.fillRect(region.boundingRect(), Qt::transparent);
    // The layer is in physical pixels: tagged with the ratio it maps one to
    // one onto the backing store.
    layer_.setDevicePixelRatio(dpr);
    if (painted_pulse_ && !focus_centre_) {
        // Never so from the manager: the whole field at the pulse.
        painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
        painter.setOpacity(pulse_);
        painter.drawImage(QPointF(0, 0), layer_);
        painter.setOpacity(1.0);
    } else if (painted_pulse_) {
        if (focus_radius_ > 0) paint_painted_focus(painter);
    } else if (!focus_centre_) {
        painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
        painter.setOpacity(pixel_opacity_);
        painter.drawImage(QPointF(0, 0), layer_);
        painter.setOpacity(1.0);
    } else if (focus_radius_ > 0) {
        const QRect bounds = logical_bounds(*focus_centre_, focus_radius_, 0);
        painter.save();
        painter.setClipRect(bounds, Qt::IntersectClip);
        painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
        painter.setOpacity(pixel_opacity_);
        painter.drawImage(QPointF(0, 0), layer_);
        painter.setOpacity(1.0);
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
}

}  // namespace umf::provider
