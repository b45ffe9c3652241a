#include "provider/screen/aim_mark.hpp"

#include <QFont>
#include <QFontMetrics>
#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace umf::provider {

namespace {

QFont title_font() {
    QFont font;
    font.setPointSizeF(kAimTitlePointSize);
    return font;
}

}  // namespace

QSize aim_mark_size(const QString& title) {
    const QFontMetrics metrics(title_font());
    const int text_width = title.isEmpty() ? 0 : metrics.horizontalAdvance(title) + 16;
    const int side = static_cast<int>(std::ceil(2 * (kAimRingRadius + kAimMargin)));
    return {side + text_width, std::max(side, metrics.height() + 8)};
}

void paint_aim_mark(QPainter& painter, QPointF c, const QString& title) {
    painter.setRenderHint(QPainter::Antialiasing);
    const QPen dark(QColor(0, 0, 0, 200), 4.0), light(Qt::white, 2.0);
    painter.setBrush(Qt::NoBrush);
    for (const QPen& pen : {dark, light}) {
        painter.setPen(pen);
        painter.drawEllipse(c, kAimRingRadius, kAimRingRadius);
    }
    if (!title.isEmpty()) {
        const QFont font = title_font();
        QPainterPath text;
        text.addText(c + QPointF(kAimRingRadius + 8, QFontMetrics(font).ascent() / 2.0 - 1), font, title);
        painter.strokePath(text, QPen(QColor(0, 0, 0, 220), 3.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
        painter.fillPath(text, Qt::white);
    }
}

AimMark aim_mark(const QString& title, double dpr) {
    dpr = dpr > 0 ? dpr : 1.0;
    const QSize logical = aim_mark_size(title);
    AimMark mark;
    mark.image = QImage((QSizeF(logical) * dpr).toSize(), QImage::Format_ARGB32_Premultiplied);
    mark.image.fill(Qt::transparent);
    mark.image.setDevicePixelRatio(dpr);
    const QPointF centre(kAimMargin + kAimRingRadius, logical.height() / 2.0);
    QPainter painter(&mark.image);
    paint_aim_mark(painter, centre, title);
    painter.end();
    mark.image.setDevicePixelRatio(1.0);
    mark.ring_centre = centre * dpr;
    return mark;
}

}  // namespace umf::provider
