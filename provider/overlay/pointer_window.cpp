#include "overlay/pointer_window.hpp"

#include <QFontMetrics>
#include <QPainter>
#include <QPainterPath>
#include <QScreen>
#include <QSurfaceFormat>
#include <cmath>

namespace umf::provider {

namespace {

QFont title_font() {
    QFont font;
    font.setPointSizeF(PointerWindow::kTitlePointSize);
    return font;
}

}  // namespace

PointerWindow::PointerWindow(QScreen* screen) {
    QSurfaceFormat format;
    format.setAlphaBufferSize(8);
    setFormat(format);
    // As the overlay's own window (overlay_window.cpp): unmanaged, on top,
    // never taking a click or the focus.
    setFlags(Qt::FramelessWindowHint | Qt::WindowStaysOnTopHint | Qt::WindowTransparentForInput |
             Qt::WindowDoesNotAcceptFocus | Qt::Tool | Qt::X11BypassWindowManagerHint);
    setTitle("umf pointer");
    if (screen) setScreen(screen);
}

void PointerWindow::point_at(QPointF point_px, const QString& title) {
    const QFontMetrics metrics(title_font());
    const int text_width = title.isEmpty() ? 0 : metrics.horizontalAdvance(title) + 16;
    const int side = static_cast<int>(std::ceil(2 * (kRingRadius + kMargin)));
    const QSize size(side + text_width, std::max(side, metrics.height() + 8));
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

void PointerWindow::paint_to(QPainter& painter) {
    painter.setCompositionMode(QPainter::CompositionMode_Source);
    painter.fillRect(QRect(QPoint(), size()), Qt::transparent);
    painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
    painter.setRenderHint(QPainter::Antialiasing);
    const QPointF c = ring_centre();
    // White on a dark outline: legible on light and dark content alike.
    const QPen dark(QColor(0, 0, 0, 200), 4.0), light(Qt::white, 2.0);
    painter.setBrush(Qt::NoBrush);
    for (const QPen& pen : {dark, light}) {
        painter.setPen(pen);
        painter.drawEllipse(c, kRingRadius, kRingRadius);
    }
    if (!title_.isEmpty()) {
        const QFont font = title_font();
        QPainterPath text;
        text.addText(c + QPointF(kRingRadius + 8, QFontMetrics(font).ascent() / 2.0 - 1), font, title_);
        painter.strokePath(text, QPen(QColor(0, 0, 0, 220), 3.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
        painter.fillPath(text, Qt::white);
    }
}

void PointerWindow::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    paint_to(painter);
}

}  // namespace umf::provider
