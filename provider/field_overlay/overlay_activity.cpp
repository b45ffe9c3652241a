#include "provider/field_overlay/overlay_activity.hpp"

#include <QMetaObject>

namespace umf::provider {

OverlayActivity::OverlayActivity(OverlayManager* manager, std::vector<int> screen_indices)
    : manager_(manager), screen_indices_(std::move(screen_indices)) {}

void OverlayActivity::set_screen_indices(std::vector<int> screen_indices) {
    std::lock_guard lock(mutex_);
    screen_indices_ = std::move(screen_indices);
}

std::optional<int> OverlayActivity::take_aim_mark(std::uint64_t session) {
    std::lock_guard lock(mutex_);
    const auto it = aim_mark_screen_.find(session);
    if (it == aim_mark_screen_.end()) return std::nullopt;
    const int index = it->second;
    aim_mark_screen_.erase(it);
    return index;
}

void OverlayActivity::seeking(std::uint64_t session) {
    // A requester that seeks has lost its lock: its ring and circle go.
    const std::optional<int> previous = take_aim_mark(session);
    OverlayManager* m = manager_;
    QMetaObject::invokeMethod(
        m,
        [m, previous] {
            if (previous) {
                m->set_aim_mark(*previous, std::nullopt, {});
                m->set_focus(*previous, std::nullopt);
            }
            m->report_seeking();
        },
        Qt::QueuedConnection);
}

void OverlayActivity::aimed(const AimActivity& aim) {
    std::optional<int> index;
    std::optional<int> previous;
    {
        std::lock_guard lock(mutex_);
        if (aim.screen && aim.screen->screen >= 0 && aim.screen->screen < static_cast<int>(screen_indices_.size()))
            index = screen_indices_[aim.screen->screen];
        if (auto it = aim_mark_screen_.find(aim.session); it != aim_mark_screen_.end()) previous = it->second;
        if (index) aim_mark_screen_[aim.session] = *index;
        else aim_mark_screen_.erase(aim.session);
    }
    OverlayManager* m = manager_;
    const QPointF at = aim.screen ? QPointF(aim.screen->x, aim.screen->y) : QPointF();
    const QString title = QString::fromStdString(aim.title);
    const double confidence = aim.confidence;
    QMetaObject::invokeMethod(
        m,
        [m, index, previous, at, title, confidence] {
            m->report_aim(confidence);
            if (previous && previous != index) {
                m->set_aim_mark(*previous, std::nullopt, {});
                m->set_focus(*previous, std::nullopt);
            }
            if (index) {
                m->set_aim_mark(*index, at, title);
                m->set_focus(*index, at);
            }
        },
        Qt::QueuedConnection);
}

void OverlayActivity::left(std::uint64_t session) {
    const std::optional<int> previous = take_aim_mark(session);
    if (!previous) return;
    OverlayManager* m = manager_;
    QMetaObject::invokeMethod(
        m,
        [m, index = *previous] {
            m->set_aim_mark(index, std::nullopt, {});
            m->set_focus(index, std::nullopt);
        },
        Qt::QueuedConnection);
}

}  // namespace umf::provider
