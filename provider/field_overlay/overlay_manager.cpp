#include "provider/field_overlay/overlay_manager.hpp"

#include <QElapsedTimer>
#include <QGuiApplication>
#include <QScreen>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "provider/desktop/x11/x11_stacking.hpp"
#include "provider/field_overlay/overlay_entry.hpp"
#include "provider/screen/desktop_layout.hpp"
#include "shared/overlay/pulse.hpp"

namespace umf::provider {

using overlay_detail::physical_size;

namespace {

constexpr double kMaxPulseHz = 60.0;
// One level of an 8-bit screen: a smaller change cannot show.
constexpr double kOpacityStep = 1.0 / 255.0;

// The preset's module size on this screen: Qt gives the physical density in
// logical pixels an inch, the ratio turns it into the screen's own pixels.
double module_px_for(const QScreen* screen, const overlay::Preset& preset) {
    return module_px_for_density(preset.module_px, screen->physicalDotsPerInch() * screen->devicePixelRatio());
}

// A screen the desktop shows no field on: it keeps its place in the layout
// (the welcome's screens stay the same) and nothing is drawn.
class AbsentSurface final : public FieldSurface {
public:
    explicit AbsentSurface(ScreenField field) : field_(std::move(field)) {}
    const ScreenField& screen_field() const override { return field_; }
    void set_field(ScreenField field, const std::vector<std::string>&) override { field_ = std::move(field); }
    void cover_screen() override {}
    void set_opacity(double opacity) override { pulse_ = opacity; }
    double pulse_opacity() const override { return pulse_; }
    void set_focus(std::optional<QPointF>, double) override {}
    void show() override {}
    void hide() override {}
    bool is_visible() const override { return false; }

private:
    ScreenField field_;
    double pulse_ = 0.0;
};

}  // namespace

OverlayManager::OverlayManager(overlay::Preset preset, std::shared_ptr<Desktop> desktop, FieldSource fields,
                               QObject* parent)
    : QObject(parent),
      preset_(std::move(preset)),
      fields_(std::move(fields)),
      desktop_(std::move(desktop)),
      x11_windows_(!desktop_ || desktop_->name() == "x11"),
      adaptive_(preset_) {
    clock_.start();
    for (QScreen* screen : QGuiApplication::screens()) add_screen(screen);
    connect(qGuiApp, &QGuiApplication::screenAdded, this, [this](QScreen* screen) {
        add_screen(screen);
        notify();
    });
    connect(qGuiApp, &QGuiApplication::screenRemoved, this, [this](QScreen* screen) {
        remove_screen(screen);
        notify();
    });
    connect(&pulse_timer_, &QTimer::timeout, this, [this] { tick(); });
    aim_mark_timer_.setSingleShot(true);
    connect(&aim_mark_timer_, &QTimer::timeout, this, [this] { expire_aim_marks(); });
    seeking_timer_.setSingleShot(true);
    seeking_timer_.setTimerType(Qt::PreciseTimer);
    connect(&seeking_timer_, &QTimer::timeout, this, [this] {
        // A timer may fire a little early: wait out the rest.
        const qint64 left = last_seeking_ms_ ? kSeekingHoldMs - (clock_.elapsed() - *last_seeking_ms_) : 0;
        if (left > 0) return seeking_timer_.start(static_cast<int>(left) + 1);
        if (circles_wanted() != circles_applied_) refocus_all();
    });
    connect(&raise_timer_, &QTimer::timeout, this, [this] {
        const std::vector<QWindow*> over = windows_over_field();
        for (QWindow* window : over) window->raise();
        QWindow* under = over.empty() ? nullptr : over.front();
        for (auto& entry : entries_) {
            raise_field(*entry, under);
            raise_ring(*entry, under);
        }
    });
    raise_timer_.start(kRaiseIntervalMs);
    // Only an X server can be asked for the desktop under the overlay.
    if (x11_windows_ && QGuiApplication::platformName() == QLatin1String("xcb")) {
        grab_ = overlay_detail::x11_grab_function();
        for (auto& entry : entries_) refocus(*entry, false);
    }
    retime();
    tick();
}

OverlayManager::~OverlayManager() = default;

void OverlayManager::add_screen(QScreen* screen) {
    auto entry = std::make_unique<Entry>();
    entry->screen = screen;
    entry->index = next_index_++;
    const QSize size = physical_size(screen);
    const ScreenField field = screen_field_for(size.width(), size.height(), module_px_for(screen, preset_), fields_);
    if (desktop_) entry->window = desktop_->make_field_surface(screen, field, preset_.palette);
    else entry->window = std::make_unique<OverlayWindow>(screen, field, preset_.palette);
    // A desktop that cannot show a field over this screen: it gets no
    // surface, and the screen still takes part in the layout.
    if (!entry->window) entry->window = std::make_unique<AbsentSurface>(field);
    entry->window->set_pixel_opacity(preset_.opacity_max);
    entry->window->set_opacity(std::max(applied_opacity_, 0.0));
    Entry* raw = entry.get();
    auto refit_this = [this, raw] {
        refit(*raw);
        notify();
    };
    connect(screen, &QScreen::geometryChanged, this, refit_this);
    connect(screen, &QScreen::physicalDotsPerInchChanged, this, refit_this);
    connect(screen, &QScreen::logicalDotsPerInchChanged, this, refit_this);
    connect(screen, &QScreen::refreshRateChanged, this, [this] { retime(); });
    entries_.push_back(std::move(entry));
    relayout();
    if (applied_opacity_ > 0 && visible_ && snapshot_depth_ == 0) raw->window->show();
    retime();
}

void OverlayManager::remove_screen(QScreen* screen) {
    disconnect(screen, nullptr, this, nullptr);
    std::erase_if(entries_, [screen](const auto& entry) { return entry->screen == screen; });
    relayout();
    retime();
}

void OverlayManager::refit(Entry& entry) {
    entry.window->cover_screen();
    relayout();
}

void OverlayManager::relayout() {
    if (entries_.empty()) {
        layout_.reset();
        return;
    }
    std::vector<DesktopScreen> desktop;
    for (const auto& entry : entries_) {
        // Qt keeps a screen's origin in native pixels and scales its size.
        const QSize size = physical_size(entry->screen);
        const QPoint origin = entry->screen->geometry().topLeft();
        desktop.push_back({entry->screen->name().toStdString(), origin.x(), origin.y(), size.width(), size.height(),
                           module_px_for(entry->screen, preset_)});
    }
    std::vector<ScreenField> fields;
    try {
        // One field over all screens, so that a field point tells the screen.
        layout_ = lay_out_desktop(desktop, fields_);
        for (const auto& laid : layout_->screens) fields.push_back(laid.field);
    } catch (const std::invalid_argument&) {
        // Mirrored (overlapping) screens: the first screen's field, which a
        // mirror of its size shows at the same place; another size shows its
        // own, which points cannot name.
        layout_ = lay_out_desktop({desktop[0]}, fields_);
        for (const auto& d : desktop)
            fields.push_back(d.width == desktop[0].width && d.height == desktop[0].height
                                 ? layout_->screens[0].field
                                 : screen_field_for(d.width, d.height, d.module_px, fields_));
    }
    for (std::size_t i = 0; i < entries_.size(); ++i) {
        const ScreenField& field = fields[i];
        const ScreenField& shown = entries_[i]->window->screen_field();
        if (!(shown.placement == field.placement) || shown.field.id != field.field.id ||
            shown.screen_width != field.screen_width || shown.screen_height != field.screen_height)
            entries_[i]->window->set_field(field, preset_.palette);
    }
    for (auto& entry : entries_) refocus(*entry, false);
}

void OverlayManager::retime() {
    double hz = 0;
    for (const auto& entry : entries_) hz = std::max(hz, entry->screen->refreshRate());
    if (hz <= 0 || hz > kMaxPulseHz) hz = kMaxPulseHz;
    pulse_timer_.setInterval(static_cast<int>(std::ceil(1000.0 / hz)));
    pulse_timer_.setTimerType(Qt::PreciseTimer);
}

void OverlayManager::set_fields(FieldSource fields) {
    fields_ = std::move(fields);
    relayout();
    notify();
}

void OverlayManager::set_preset(const overlay::Preset& preset) {
    const bool new_palette = preset.palette != preset_.palette;
    const bool new_module = preset.module_px != preset_.module_px;
    preset_ = preset;
    adaptive_ = overlay::AdaptiveOverlay(preset_);
    for (auto& entry : entries_) {
        if (new_palette) entry->window->set_field(entry->window->screen_field(), preset_.palette);
        entry->window->set_pixel_opacity(std::max(preset_.opacity_max, entry->window->pulse_opacity()));
        refocus(*entry, false);
    }
    if (new_module) {
        relayout();
        notify();
    }
    pulse_timer_.start();
    tick();
}

void OverlayManager::note_request() {
    last_request_ms_ = clock_.elapsed();
    if (!pulse_timer_.isActive()) pulse_timer_.start();
    tick();
}

void OverlayManager::report_aim(double confidence) {
    const double radius = adaptive_.focus_radius_modules();
    adaptive_.aim(static_cast<double>(clock_.elapsed()) / 1000.0, confidence);
    if (adaptive_.focus_radius_modules() != radius)
        for (auto& entry : entries_) refocus(*entry, false);
    note_request();
}

void OverlayManager::report_seeking() {
    const double radius = adaptive_.focus_radius_modules();
    adaptive_.seeking(static_cast<double>(clock_.elapsed()) / 1000.0);
    last_seeking_ms_ = clock_.elapsed();
    seeking_timer_.start(kSeekingHoldMs);
    if (adaptive_.focus_radius_modules() != radius || circles_wanted() != circles_applied_) refocus_all();
    note_request();
}

bool OverlayManager::circles_wanted() const {
    if (preset_.region != overlay::Region::focus) return false;
    if (last_seeking_ms_ && clock_.elapsed() - *last_seeking_ms_ < kSeekingHoldMs) return false;
    return std::any_of(entries_.begin(), entries_.end(), [](const auto& e) { return e->focus.has_value(); });
}

void OverlayManager::refocus_all() {
    for (auto& entry : entries_) refocus(*entry, false);
}

void OverlayManager::tick() {
    const qint64 now = clock_.elapsed();
    std::optional<double> since;
    if (last_request_ms_) since = static_cast<double>(now - *last_request_ms_) / 1000.0;
    const double presence = overlay::presence(preset_, since);
    // The preset's pulse, lowered while requesters lock easily.
    const double opacity = adaptive_.opacity(static_cast<double>(now) / 1000.0) * presence;
    if (std::abs(opacity - applied_opacity_) >= kOpacityStep || (opacity == 0) != (applied_opacity_ == 0))
        apply_shown(opacity);
    // Nothing moves until the next request or preset: no wake-ups meanwhile.
    const bool idle = presence == 0 || (presence == 1 && preset_.activation == overlay::Activation::always &&
                                        preset_.period_s == 0);
    if (idle)
        pulse_timer_.stop();
    else if (!pulse_timer_.isActive())
        pulse_timer_.start();
}

void OverlayManager::apply_shown(double opacity) {
    applied_opacity_ = opacity;
    // An invisible field is unmapped rather than composited at opacity 0.
    const bool shown = visible_ && snapshot_depth_ == 0 && opacity > 0;
    for (auto& entry : entries_) {
        FieldSurface& window = *entry->window;
        if (shown) {
            window.set_opacity(opacity);
            if (!window.is_visible()) {
                // Stacked before it is mapped: mapped first where it was, it
                // could show over a card for a moment.
                QWindow* under = lowest_window_over_field();
                if (under) window.raise_under(*under);
                window.show();
                if (!under) window.raise();
            }
        } else if (window.is_visible()) {
            window.hide();
        }
        show_aim_mark(*entry);
    }
}

std::vector<QWindow*> OverlayManager::windows_over_field() const {
    // The offscreen platform cannot raise.
    if (!windows_over_field_ || QGuiApplication::platformName() == QLatin1String("offscreen")) return {};
    return windows_over_field_();
}

QWindow* OverlayManager::lowest_window_over_field() const {
    const std::vector<QWindow*> over = windows_over_field();
    return over.empty() ? nullptr : over.front();
}

void OverlayManager::raise_field(Entry& entry, QWindow* under) {
    if (!entry.window->is_visible()) return;
    if (under)
        entry.window->raise_under(*under);
    else
        entry.window->raise();
}

void OverlayManager::raise_ring(Entry& entry, QWindow* under) {
    if (!entry.aim_window || !entry.aim_window->isVisible()) return;
    if (under)
        stack_under(*entry.aim_window, *under);
    else
        entry.aim_window->raise();
}

OverlayManager::Entry* OverlayManager::entry_for(int index) {
    for (auto& entry : entries_)
        if (entry->index == index) return entry.get();
    return nullptr;
}

void OverlayManager::set_focus(int index, std::optional<QPointF> centre_px) {
    Entry* entry = entry_for(index);
    if (!entry) return;
    entry->focus = centre_px;
    if (circles_wanted() != circles_applied_)
        refocus_all();
    else
        refocus(*entry, true);
}

void OverlayManager::refocus(Entry& entry, bool aimed) {
    circles_applied_ = circles_wanted();
    const bool circles = circles_applied_;
    const double module_px = entry.window->screen_field().placement.module_px;
    const double radius = adaptive_.focus_radius_modules() * module_px;
    const bool painted = backdrop_mode() && circles && entry.window->supports_painted_pulse();
    entry.window->set_painted_pulse(painted);
    // Circles: this screen's, or none here (a requester is locked elsewhere).
    // Otherwise the whole field, for the requesters still seeking a lock.
    entry.window->set_focus(circles ? std::optional<QPointF>(entry.focus.value_or(QPointF(-1e6, -1e6)))
                                    : std::nullopt,
                            radius);
    if (!painted) {
        // The window dropped its backdrop; the raw grab goes too.
        entry.raw = QImage();
        entry.grab_failed = false;
        entry.grab_wanted = false;
        entry.blurred_strength = entry.blurred_module_px = -1.0;
        return;
    }
    // Another strength or module size (the tuning window): the same grab
    // blurred again, no new grab.
    if (!entry.raw.isNull() && (entry.blurred_strength != preset_.blur || entry.blurred_module_px != module_px))
        blur_backdrop(entry);
    if (entry.focus && needs_grab(entry, *entry.focus, radius, aimed)) {
        entry.grab_wanted = true;
        request_grab();
    }
}

void OverlayManager::set_aim_mark(int index, std::optional<QPointF> point_px, const QString& title) {
    Entry* entry = entry_for(index);
    if (!entry) return;
    entry->pointing = point_px.has_value();
    if (point_px) {
        if (x11_windows_) {
            if (!entry->aim_window) entry->aim_window = std::make_unique<AimWindow>(entry->screen);
            entry->aim_window->point_at(*point_px, title);
        }
        entry->pointed_px = *point_px;
        entry->pointed_title = title;
        entry->pointed_ms = clock_.elapsed();
        aim_mark_timer_.start(kAimMarkHoldMs);
    }
    show_aim_mark(*entry);
}

void OverlayManager::show_aim_mark(Entry& entry) {
    // With the field: not in a snapshot, not while the overlay is off or faded out.
    const bool shown = entry.pointing && visible_ && snapshot_depth_ == 0 && applied_opacity_ > 0;
    if (!x11_windows_) {
        // The surface draws the ring into its own pixels (Wayland).
        entry.window->set_aim_mark(shown ? std::optional<QPointF>(entry.pointed_px) : std::nullopt, entry.pointed_title);
        return;
    }
    if (!entry.aim_window) return;
    if (shown) {
        // Above the field's window, which may have been raised since, and
        // under the cards; stacked before it is mapped, as the field.
        AimWindow& ring = *entry.aim_window;
        QWindow* under = lowest_window_over_field();
        if (under) stack_under(ring, *under);
        if (!ring.isVisible()) ring.show();
        if (!under) ring.raise();
    } else if (!shown && entry.aim_window->isVisible()) {
        entry.aim_window->hide();
    }
}

void OverlayManager::expire_aim_marks() {
    // A requester that stopped aiming without seeking or leaving (a phone
    // put down with the page open) leaves no ring behind.
    const qint64 now = clock_.elapsed();
    qint64 next = -1;
    for (auto& entry : entries_) {
        if (!entry->pointing) continue;
        const qint64 left = kAimMarkHoldMs - (now - entry->pointed_ms);
        if (left <= 0) {
            entry->pointing = false;
            show_aim_mark(*entry);
        } else if (next < 0 || left < next) {
            next = left;
        }
    }
    if (next >= 0) aim_mark_timer_.start(static_cast<int>(next) + 1);
}

std::vector<AimWindow*> OverlayManager::aim_windows() const {
    std::vector<AimWindow*> out;
    for (const auto& entry : entries_)
        if (entry->aim_window && entry->aim_window->isVisible()) out.push_back(entry->aim_window.get());
    return out;
}

void OverlayManager::set_visible(bool visible) {
    visible_ = visible;
    apply_shown(std::max(applied_opacity_, 0.0));
}

void OverlayManager::hide_for_snapshot() {
    ++snapshot_depth_;
    apply_shown(std::max(applied_opacity_, 0.0));
}

void OverlayManager::show_after_snapshot() {
    snapshot_depth_ = std::max(0, snapshot_depth_ - 1);
    apply_shown(std::max(applied_opacity_, 0.0));
}

std::vector<OverlayScreen> OverlayManager::screens() const {
    std::vector<OverlayScreen> out;
    for (const auto& entry : entries_) {
        // Qt keeps a screen's origin in native pixels and scales its size:
        // the root rectangle is the origin with the physical size.
        const QSize size = physical_size(entry->screen);
        out.push_back({entry->index, entry->screen->name(),
                       QRect(entry->screen->geometry().topLeft(), size), entry->window->screen_field()});
    }
    return out;
}

std::vector<int> OverlayManager::layout_indices() const {
    std::vector<int> out;
    // Mirrored screens: only the first is in the layout.
    for (std::size_t i = 0; i < entries_.size() && layout_ && i < layout_->screens.size(); ++i)
        out.push_back(entries_[i]->index);
    return out;
}

std::vector<FieldSurface*> OverlayManager::surfaces() const {
    std::vector<FieldSurface*> out;
    for (const auto& entry : entries_) out.push_back(entry->window.get());
    return out;
}

std::vector<OverlayWindow*> OverlayManager::windows() const {
    std::vector<OverlayWindow*> out;
    for (const auto& entry : entries_)
        if (auto* window = dynamic_cast<OverlayWindow*>(entry->window.get())) out.push_back(window);
    return out;
}

void OverlayManager::notify() {
    if (screens_changed_) screens_changed_();
}

}  // namespace umf::provider
