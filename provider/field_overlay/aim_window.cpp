#include "provider/field_overlay/aim_window.hpp"

#include "provider/screen/aim_mark.hpp"

#include <QPainter>
#include <QScreen>
#include <QSurfaceFormat>
#include <cmath>

namespace umf::provider {

AimWindow::AimWindow(QScreen* screen) {
    QSurfaceFormat format;
    format.setAlphaBufferSize(8);
    setFormat(format);
    // As the overlay's own window (overlay_window.cpp): unmanaged, on top,
    // never taking a click or the focus.
    setFlags(Qt::FramelessWindowHint | Qt::WindowStaysOnTopHint | Qt::WindowTransparentForInput |
             Qt::WindowDoesNotAcceptFocus | Qt::Tool | Qt::X11BypassWindowManagerHint);
    setTitle("umf aim mark");
    if (screen) setScreen(screen);
}

void AimWindow::point_at(QPointF point_px, const QString& title) {
    const QSize size = aim_mark_size(title);
    const double dpr = devicePixelRatio();
    const QPoint origin = screen() ? screen()->geometry().topLeft() : QPoint();
    // The ring's centre on the point: Qt places windows in logical pixels
    // from the screen's origin.
    const QPoint top_left = origin + QPoint(static_cast<int>(std::lround(point_px.x() / dpr - kMargin - kRingRadius)),
                                            static_cast<int>(std::lround(point_px.y() / dpr - size.height() / 2.0)));
    const bool new_title = title != title_;
    title_ = title;
    if (geometry() != QRect(top_left, size)) setGeometry(QRect(top_left, size));
    if (new_title) update();
}

void AimWindow::paint_to(QPainter& painter) {
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.fillRect(QRect(QPoint(), size()), Qt::transparent);
    painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
    paint_aim_mark(painter, ring_centre(), title_);
}

void AimWindow::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    paint_to(painter);
}

}  // namespace umf::provider
