// The overlay over the whole desktop: one OverlayWindow per screen, kept in
// step with the screens as they come, go and change, pulsing at the preset's
// opacity. The pulse runs on a timer at the display's refresh rate (at most
// 60 Hz) and touches a window only when the opacity moved by a level the
// screen can show.
//
// The screens share one field (screen/desktop_layout.hpp), each showing its
// own part, so a field point names the screen; mirrored screens, which
// overlap, each show the field of their own size instead.
#pragma once

#include <QElapsedTimer>
#include <QObject>
#include <QPointF>
#include <QRect>
#include <QString>
#include <QTimer>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "overlay/adaptive.hpp"
#include "overlay/overlay_window.hpp"
#include "overlay/preset.hpp"
#include "screen/desktop_layout.hpp"

class QScreen;

namespace umf::provider {

struct OverlayScreen {
    int index = 0;      // stable while the screen stays
    QString name;       // QScreen::name(), e.g. "DP-1"
    QRect root_rect;    // in the root window's (virtual desktop's) pixels
    ScreenField field;  // at the screen's physical pixel size
};

class OverlayManager : public QObject {
public:
    explicit OverlayManager(overlay::Preset preset, QObject* parent = nullptr);
    ~OverlayManager() override;

    void set_preset(const overlay::Preset& preset);
    const overlay::Preset& preset() const { return preset_; }

    // A requester seeks or aims: an on-demand field comes up (and fades out
    // after the last one, overlay::presence).
    void note_request();
    // What requesters report (overlay/adaptive.hpp): an aim with the
    // detector's confidence, or seeking without a lock. Easy locks lower the
    // field within the preset's range, struggling raises it and grows the
    // focus region. Both also count as a request.
    void report_aim(double confidence);
    void report_seeking();
    // With Region::focus, where the field is shown on screen `index`, in its
    // physical pixels; nullopt hides the focus there. Ignored for Region::full.
    void set_focus(int index, std::optional<QPointF> centre_px);
    void set_pointer(int index, std::optional<QPointF> point_px, const QString& title);

    void set_visible(bool visible);
    bool visible() const { return visible_; }
    // Around a snapshot of the screen, which must not hold the field. Nested
    // calls are counted. The windows are unmapped at once; the compositor
    // redraws the screen within a frame or two, so the caller waits
    // kSnapshotSettleMs before capturing.
    void hide_for_snapshot();
    void show_after_snapshot();
    static constexpr int kSnapshotSettleMs = 50;

    std::vector<OverlayScreen> screens() const;
    // The field over the screens as the service should know it (nullopt
    // without screens): layout()->screens[i] is the screen with index
    // layout_indices()[i]. Mirrored screens give the first alone.
    const std::optional<DesktopLayout>& layout() const { return layout_; }
    std::vector<int> layout_indices() const;
    // Called after screens() or layout() changed: a screen came, went or
    // changed size or density, or the preset's module size changed.
    void on_screens_changed(std::function<void()> callback) { screens_changed_ = std::move(callback); }

    // The windows, for tests and diagnostics.
    std::vector<OverlayWindow*> windows() const;
    // The opacity last given to the windows.
    double opacity() const { return applied_opacity_; }

private:
    struct Entry;

    void add_screen(QScreen* screen);
    void remove_screen(QScreen* screen);
    void refit(Entry& entry);
    void relayout();
    void tick();
    void retime();
    void apply_shown(double opacity);
    Entry* entry_for(int index);
    void notify();

    overlay::Preset preset_;
    overlay::AdaptiveOverlay adaptive_;
    std::vector<std::unique_ptr<Entry>> entries_;
    std::optional<DesktopLayout> layout_;
    int next_index_ = 0;
    QElapsedTimer clock_;
    std::optional<qint64> last_request_ms_;
    QTimer pulse_timer_;
    QTimer raise_timer_;
    double applied_opacity_ = -1.0;
    bool visible_ = true;
    int snapshot_depth_ = 0;
    std::function<void()> screens_changed_;
};

}  // namespace umf::provider
