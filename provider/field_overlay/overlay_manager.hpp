// The overlay over the whole desktop: one OverlayWindow per screen, kept in
// step with the screens as they come, go and change, pulsing at the preset's
// opacity. The pulse runs on a timer at the display's refresh rate (at most
// 60 Hz) and touches a window only when the opacity moved by a level the
// screen can show.
//
// The screens share one field (screen/desktop_layout.hpp), each showing its
// own part, so a field point names the screen; mirrored screens, which
// overlap, each show the field of their own size instead.
//
// Region::focus with a preset's blur: the screen under each focus circle is
// grabbed without the overlay (the windows hidden for a moment), blurred and
// given to the window, which then paints the pulse inside the circle itself
// (OverlayWindow, "painted pulse"). A grab is made when the circle has no
// backdrop near it: it moved by more than a quarter of its radius, grew out
// of the grabbed area, or the grab is older than kBackdropMaxAgeMs while the
// requester keeps aiming. Grabs run on the Qt thread without blocking it
// (hide, a timer for the compositor to settle, capture, show), one at a
// time, requests in the meantime coalesced, at most one started every
// kMinGrabIntervalMs. Every other mode keeps the compositor's opacity.
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

#include "provider/desktop/x11/overlay_window.hpp"
#include "provider/field_overlay/aim_window.hpp"
#include "provider/screen/desktop_layout.hpp"
#include "shared/overlay/adaptive.hpp"
#include "shared/overlay/preset.hpp"

class QScreen;
class QWindow;

namespace umf::provider {

struct OverlayScreen {
    int index = 0;      // stable while the screen stays
    QString name;       // QScreen::name(), e.g. "DP-1"
    QRect root_rect;    // in the root window's (virtual desktop's) pixels
    ScreenField field;  // at the screen's physical pixel size
};

class OverlayManager : public QObject {
public:
    // The field's surfaces come from `desktop` (desktop/desktop.hpp); without
    // one they are X11 windows (desktop/x11/overlay_window.hpp), as on Qt's
    // xcb and offscreen platforms. The aim ring's own window and the
    // blurred backdrop are X11 only. `fields`: the shipped fields or the
    // screen's own (screen/field_source.hpp).
    explicit OverlayManager(overlay::Preset preset, std::shared_ptr<Desktop> desktop = nullptr,
                            FieldSource fields = {}, QObject* parent = nullptr);
    ~OverlayManager() override;

    void set_preset(const overlay::Preset& preset);
    const overlay::Preset& preset() const { return preset_; }
    // Another field source (the screen's new seed, `pair --rotate --field`):
    // every screen shows its new field, and on_screens_changed's callback
    // tells the service, as when screens change.
    void set_fields(FieldSource fields);

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
    // physical pixels; nullopt: no requester is locked there. Ignored for
    // Region::full. A phone needs the field to lock at all, so a focus preset
    // shows the whole field while no requester is locked anywhere and for
    // kSeekingHoldMs after any report of seeking; otherwise only the circles,
    // and nothing on screens without one.
    void set_focus(int index, std::optional<QPointF> centre_px);
    static constexpr int kSeekingHoldMs = 1000;
    // Whether focus circles are what is shown now (see set_focus).
    bool circles_shown() const { return circles_applied_; }
    // The ring and title where a requester points on screen `index`
    // (physical pixels), in a window of its own that does not pulse; nullopt
    // removes it. A ring not moved for kAimMarkHoldMs goes by itself.
    void set_aim_mark(int index, std::optional<QPointF> point_px, const QString& title);
    static constexpr int kAimMarkHoldMs = 2000;
    // The aim windows shown now, for tests.
    std::vector<AimWindow*> aim_windows() const;

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
    // The provider's own windows that belong over the field (the put
    // cards), those shown now, lowest first. Each time the field's windows
    // are raised (every kRaiseIntervalMs, to stay over windows mapped since)
    // these are raised first, and the field's and the ring's windows then go
    // right under the lowest of them (desktop/x11/x11_stacking.hpp): no
    // restack leaves the field over a card, not even for a frame.
    void set_windows_over_field(std::function<std::vector<QWindow*>()> windows) {
        windows_over_field_ = std::move(windows);
    }
    // How often the windows are raised again (OverlayWindow's flags): rare
    // enough to cost nothing, often enough that a window put above them by
    // the window manager covers the field only briefly.
    static constexpr int kRaiseIntervalMs = 1000;

    // The screen in `root_rect` (root-window pixels, within one screen) as it
    // is without the overlay; a null image when it cannot be had. The default
    // captures with X11 (desktop/x11/x11_desktop.hpp) on the xcb platform and is
    // empty elsewhere: without a grab function the blur is not applied to the
    // overlay. Tests give a synthetic one. Setting it drops grabbed backdrops.
    using GrabFunction = std::function<QImage(const QRect& root_rect)>;
    void set_grab_function(GrabFunction grab);
    static constexpr int kBackdropMaxAgeMs = 2000;
    static constexpr int kMinGrabIntervalMs = 300;
    // Whether a grab is scheduled or waiting for the compositor.
    bool grab_pending() const { return grab_state_ != GrabState::idle; }
    // Milliseconds the last grab's capture and blur took (not the settling).
    double last_grab_cost_ms() const { return last_grab_cost_ms_; }

    // The surfaces, and those that are X11 windows, for tests and diagnostics.
    std::vector<FieldSurface*> surfaces() const;
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
    // set_focus's work; `aimed` when a requester aimed just now (an old
    // backdrop is then grabbed again).
    void refocus(Entry& entry, bool aimed);
    // Every screen's refocus, when circles_shown() changes.
    void refocus_all();
    void show_aim_mark(Entry& entry);
    // set_windows_over_field's windows where they can be stacked (none on
    // the offscreen platform), and the lowest of them (nullptr: none).
    std::vector<QWindow*> windows_over_field() const;
    QWindow* lowest_window_over_field() const;
    // The entry's field window, or its ring's, to the top or right under
    // `under` (the ring raised after the field goes above it).
    void raise_field(Entry& entry, QWindow* under);
    void raise_ring(Entry& entry, QWindow* under);
    void expire_aim_marks();
    bool circles_wanted() const;
    // Region::focus with a blur and a way to grab: the painted pulse.
    bool backdrop_mode() const;
    bool needs_grab(const Entry& entry, QPointF centre, double radius, bool aimed) const;
    void request_grab();
    void start_grab();
    void finish_grab();
    // The entry's raw grab blurred at the preset's strength, to its window.
    void blur_backdrop(Entry& entry);

    overlay::Preset preset_;
    FieldSource fields_;
    std::shared_ptr<Desktop> desktop_;
    bool x11_windows_ = true;  // surfaces and aim rings are Qt windows on X11
    overlay::AdaptiveOverlay adaptive_;
    std::vector<std::unique_ptr<Entry>> entries_;
    std::optional<DesktopLayout> layout_;
    int next_index_ = 0;
    QElapsedTimer clock_;
    std::optional<qint64> last_request_ms_;
    std::optional<qint64> last_seeking_ms_;
    bool circles_applied_ = false;
    QTimer seeking_timer_;
    QTimer aim_mark_timer_;  // fires when kSeekingHoldMs has passed since the last seeking
    QTimer pulse_timer_;
    QTimer raise_timer_;
    double applied_opacity_ = -1.0;
    bool visible_ = true;
    int snapshot_depth_ = 0;
    std::function<void()> screens_changed_;
    std::function<std::vector<QWindow*>()> windows_over_field_;
    GrabFunction grab_;
    enum class GrabState { idle, scheduled, settling };
    GrabState grab_state_ = GrabState::idle;
    std::optional<qint64> last_grab_ms_;  // when the last grab was captured
    double last_grab_cost_ms_ = 0.0;
};

}  // namespace umf::provider
