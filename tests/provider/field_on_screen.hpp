// What the tests of the field's layer surface on a real compositor (Sway,
// KWin) check in screenshots of the desktop taken before and with it: how
// far the field moved the pixels under it, the pointer ring's extremes and
// its title.
#pragma once

#include <QCoreApplication>
#include <QImage>
#include <QPointF>
#include <QRect>
#include <QSize>
#include <QString>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <chrono>
#include <thread>
#include <utility>

#include "provider/desktop/wlroots/layer_field_surface.hpp"
#include "provider/screen/aim_mark.hpp"

namespace umf::test {

// Turns Qt's events and the surface's own Wayland connection for a while:
// the tests have no event loop running.
inline void pump(provider::LayerFieldSurface& surface, std::chrono::milliseconds how_long) {
    const auto end = std::chrono::steady_clock::now() + how_long;
    while (std::chrono::steady_clock::now() < end) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
        surface.dispatch_pending();
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
}

// The largest change of one channel between two pixels.
inline int channel_change(QRgb p, QRgb q) {
    return std::max({std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)), std::abs(qBlue(p) - qBlue(q))});
}

// The largest change of one channel between two screenshots within `area`
// (every `step`-th pixel of a row).
inline int largest_change(const QImage& a, const QImage& b, const QRect& area, int step = 1) {
    int worst = 0;
    for (int y = area.top(); y <= area.bottom(); ++y)
        for (int x = area.left(); x <= area.right(); x += step)
            worst = std::max(worst, channel_change(a.pixel(x, y), b.pixel(x, y)));
    return worst;
}

// Of the pixels the field's layer covers (opaque in `layer`, from
// field_layer()) within `area`: how many, and how many the field moved by
// `by` or more between the screenshots.
struct FieldChange {
    long field_pixels = 0;
    long changed = 0;
};
inline FieldChange field_change(const QImage& before, const QImage& with, const QImage& layer, const QRect& area,
                                int by = 8) {
    FieldChange out;
    for (int y = area.top(); y <= area.bottom(); ++y)
        for (int x = area.left(); x <= area.right(); ++x) {
            if (qAlpha(layer.pixel(x, y)) == 0) continue;
            ++out.field_pixels;
            out.changed += channel_change(before.pixel(x, y), with.pixel(x, y)) >= by;
        }
    return out;
}

// Around the ring drawn at `point`: the brightest of its pixels' darkest
// channel and the darkest of their brightest channel. The ring is white on
// a dark outline: one near 255 and one near 0, which a faint field over
// windows never makes.
inline std::pair<int, int> ring_extremes(const QImage& shot, const QPointF& point) {
    int brightest = 0, darkest = 255;
    for (int k = 0; k < 360; k += 3) {
        const double a = k * M_PI / 180.0;
        for (const double r : {provider::kAimRingRadius - 1, provider::kAimRingRadius, provider::kAimRingRadius + 1}) {
            const QRgb p = shot.pixel(static_cast<int>(std::lround(point.x() + r * std::cos(a))),
                                      static_cast<int>(std::lround(point.y() + r * std::sin(a))));
            brightest = std::max(brightest, std::min({qRed(p), qGreen(p), qBlue(p)}));
            darkest = std::min(darkest, std::max({qRed(p), qGreen(p), qBlue(p)}));
        }
    }
    return {brightest, darkest};
}

// The pixels of the title drawn beside a ring at `point` that are white
// (every channel 235 or more), which a faint field over windows of middle
// tones never makes.
inline long white_title_pixels(const QImage& shot, const QPointF& point, const QString& title) {
    const QSize size = provider::aim_mark_size(title);
    const double ring = provider::kAimMargin + provider::kAimRingRadius;
    const QRect box(static_cast<int>(point.x() + provider::kAimRingRadius + 2),
                    static_cast<int>(point.y() - size.height() / 2.0),
                    static_cast<int>(size.width() - 2 * ring), size.height());
    long white = 0;
    for (int y = box.top(); y <= box.bottom(); ++y)
        for (int x = box.left(); x <= box.right(); ++x) {
            const QRgb p = shot.pixel(x, y);
            white += std::min({qRed(p), qGreen(p), qBlue(p)}) >= 235;
        }
    return white;
}

}  // namespace umf::test
