// Where a phone points, as drawn on the screen: a ring at the aim point and
// the title of what a grab would take beside it, white on a dark outline so
// it reads on light and dark content alike. Drawn at full strength, apart
// from the field's pulse: on X11 in a window of its own
// (overlay/aim_window.hpp), on Wayland into the field's own surface.
#pragma once

#include <QImage>
#include <QPointF>
#include <QSize>
#include <QString>

class QPainter;

namespace umf::provider {

inline constexpr double kAimRingRadius = 18.0;  // logical pixels: the same apparent size on any screen
inline constexpr double kAimTitlePointSize = 11.0;
inline constexpr double kAimMargin = 4.0;

// The logical size the ring and `title` take, the ring's centre at
// (kAimMargin + kAimRingRadius, height / 2).
QSize aim_mark_size(const QString& title);

// Draws them with the ring's centre at `ring_centre` (logical pixels).
void paint_aim_mark(QPainter& painter, QPointF ring_centre, const QString& title);

struct AimMark {
    QImage image;         // Format_ARGB32_Premultiplied, physical pixels
    QPointF ring_centre;  // within the image, physical pixels
};

// The mark on its own, at `dpr` physical pixels a logical one.
AimMark aim_mark(const QString& title, double dpr);

}  // namespace umf::provider
