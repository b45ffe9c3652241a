// Where a phone points, shown apart from the field: a ring at the aim point
// and the title of what a grab would take beside it, in a small window of
// its own. In the field's window it would pulse and fade with the field,
// which at a subtle preset leaves it too faint to read; here it is drawn at
// full strength, click-through and never focused like the overlay.
#pragma once

#include <QPointF>
#include <QRasterWindow>
#include <QString>

#include "provider/screen/aim_mark.hpp"

class QScreen;

namespace umf::provider {

class AimWindow : public QRasterWindow {
public:
    explicit AimWindow(QScreen* screen);

    // Moves to `point_px` (the screen's physical pixels, as the placement)
    // with `title`; the window is sized to the ring and the title.
    void point_at(QPointF point_px, const QString& title);
    const QString& title() const { return title_; }
    // Where the ring's centre is within the window, in logical pixels.
    QPointF ring_centre() const { return {kMargin + kRingRadius, height() / 2.0}; }

    // Draws the ring and title as paintEvent does (tests render it).
    void paint_to(QPainter& painter);

    static constexpr double kRingRadius = kAimRingRadius;
    static constexpr double kTitlePointSize = kAimTitlePointSize;

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    static constexpr double kMargin = kAimMargin;

    QString title_;
};

}  // namespace umf::provider
