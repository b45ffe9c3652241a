// OverlayManager's backdrop: the desktop under the focus circle, grabbed
// with the field hidden, blurred and shown inside the circle (the preset's
// background blur on a live desktop).
#include <QElapsedTimer>
#include <QTimer>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "provider/desktop/x11/x11_desktop.hpp"
#include "provider/field_overlay/overlay_entry.hpp"
#include "shared/overlay/background_blur.hpp"

namespace umf::provider {

using overlay_detail::blur_margin_px;
using overlay_detail::circle_bounds;
using overlay_detail::physical_size;

namespace {

// The default grab: the root window's pixels through X11, on the display Qt
// uses, opened at the first grab. Null images when there is none.
class X11Grab {
public:
    QImage operator()(const QRect& root_rect) {
        try {
            if (!desktop_) desktop_ = std::make_shared<X11Desktop>();
            const Capture shot = desktop_->capture({root_rect.x(), root_rect.y(), root_rect.width(), root_rect.height()});
            if (shot.pixels.empty() || shot.width <= 0 || shot.height <= 0) return {};
            // 0xffRRGGBB a pixel: Format_RGB32's own layout.
            QImage image(shot.width, shot.height, QImage::Format_RGB32);
            if (image.isNull()) return {};
            for (int y = 0; y < shot.height; ++y)
                std::memcpy(image.scanLine(y), &shot.pixels[static_cast<std::size_t>(y) * shot.width],
                            static_cast<std::size_t>(shot.width) * 4);
            return image;
        } catch (const std::exception&) {
            return {};
        }
    }

private:
    std::shared_ptr<X11Desktop> desktop_;
};

}  // namespace

OverlayManager::GrabFunction overlay_detail::x11_grab_function() { return X11Grab(); }

bool OverlayManager::backdrop_mode() const {
    // Only the focus circle is blurred on a live desktop. Full-region blur
    // stays unsupported here: the window cannot see through itself, so it
    // would have to show a still grab of the whole desktop, opaque, which
    // freezes what the user sees (typing, scrolling, video) until the next
    // grab, and each grab blinks the whole field off. A focus circle is
    // small, follows the aim and is grabbed again as it moves or ages.
    return preset_.region == overlay::Region::focus && preset_.blur > 0 && grab_;
}

bool OverlayManager::needs_grab(const Entry& entry, QPointF centre, double radius, bool aimed) const {
    const qint64 age = clock_.elapsed() - entry.grabbed_ms;
    if (entry.grab_failed) return age > kBackdropMaxAgeMs;
    if (entry.raw.isNull()) return true;
    const QRect screen(QPoint(), physical_size(entry.screen));
    const QRect circle = circle_bounds(centre, radius, 0).intersected(screen);
    if (circle.isEmpty()) return false;  // off this screen: nothing to show
    if (!entry.good_rect.contains(circle)) return true;
    if (std::hypot(centre.x() - entry.grabbed_centre.x(), centre.y() - entry.grabbed_centre.y()) > radius / 4)
        return true;
    // The content may have changed under a circle that stays.
    return aimed && age > kBackdropMaxAgeMs;
}

void OverlayManager::request_grab() {
    if (grab_state_ != GrabState::idle) return;  // coalesced: finish_grab serves every entry that wants one
    qint64 wait = 0;
    if (last_grab_ms_) wait = std::max<qint64>(0, kMinGrabIntervalMs - (clock_.elapsed() - *last_grab_ms_));
    grab_state_ = GrabState::scheduled;
    QTimer::singleShot(static_cast<int>(wait), this, [this] { start_grab(); });
}

void OverlayManager::start_grab() {
    const bool wanted = std::any_of(entries_.begin(), entries_.end(), [](const auto& e) { return e->grab_wanted; });
    if (!wanted || !backdrop_mode()) {
        grab_state_ = GrabState::idle;
        return;
    }
    grab_state_ = GrabState::settling;
    // The windows are unmapped; the compositor redraws the desktop without
    // them within a frame or two.
    hide_for_snapshot();
    QTimer::singleShot(kSnapshotSettleMs, this, [this] { finish_grab(); });
}

void OverlayManager::finish_grab() {
    QElapsedTimer cost;
    cost.start();
    const qint64 now = clock_.elapsed();
    for (auto& entry : entries_) {
        if (!entry->grab_wanted) continue;
        entry->grab_wanted = false;
        if (!entry->focus || !backdrop_mode()) continue;
        // Where the circle is now: it may have moved while the desktop settled.
        const QPointF centre = *entry->focus;
        const double module_px = entry->window->screen_field().placement.module_px;
        const double radius = adaptive_.focus_radius_modules() * module_px;
        const QRect screen(QPoint(), physical_size(entry->screen));
        // Room for the circle to move by a quarter of its radius.
        const QRect good = circle_bounds(centre, radius, radius / 4 + 1).intersected(screen);
        const int margin = blur_margin_px(module_px);
        const QRect rect = good.adjusted(-margin, -margin, margin, margin).intersected(screen);
        entry->grabbed_ms = now;
        entry->grabbed_centre = centre;
        QImage image;
        if (!good.isEmpty()) image = grab_(rect.translated(entry->screen->geometry().topLeft()));
        if (image.isNull() || image.size() != rect.size()) {
            entry->raw = QImage();
            entry->grab_failed = !good.isEmpty();
            entry->window->set_backdrop({}, {});
            continue;
        }
        entry->grab_failed = false;
        entry->raw = image.convertToFormat(QImage::Format_RGB32);
        entry->raw_rect = rect;
        entry->good_rect = good;
        blur_backdrop(*entry);
    }
    last_grab_ms_ = clock_.elapsed();
    last_grab_cost_ms_ = static_cast<double>(cost.nsecsElapsed()) / 1e6;
    grab_state_ = GrabState::idle;
    show_after_snapshot();
}

void OverlayManager::blur_backdrop(Entry& entry) {
    const double module_px = entry.window->screen_field().placement.module_px;
    QImage blurred = entry.raw.copy();
    // RGB32 is B, G, R, padding in memory on little-endian; the blur treats
    // the three colour bytes alike, so only the 4th byte's place matters.
    const overlay::PixelBuffer pixels{blurred.bits(), blurred.width(), blurred.height(), blurred.bytesPerLine(), 4,
                                      true};
    if (!overlay::blur_background(pixels, {0, 0, blurred.width(), blurred.height()}, std::clamp(preset_.blur, 0.0, 1.0),
                                  module_px)) {
        entry.window->set_backdrop({}, {});
        return;
    }
    entry.blurred_strength = preset_.blur;
    entry.blurred_module_px = module_px;
    // The window gets the part whose blur saw all it needed.
    entry.window->set_backdrop(blurred.copy(entry.good_rect.translated(-entry.raw_rect.topLeft())),
                               entry.good_rect.topLeft());
}

void OverlayManager::set_grab_function(GrabFunction grab) {
    grab_ = std::move(grab);
    for (auto& entry : entries_) {
        entry->raw = QImage();
        entry->grab_failed = false;
        entry->window->set_backdrop({}, {});
        refocus(*entry, false);
    }
}

}  // namespace umf::provider
