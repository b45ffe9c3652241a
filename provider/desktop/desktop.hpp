// The desktop seam: everything the provider asks of a desktop session, behind
// one interface with one folder per backend (desktop/x11, desktop/wlroots,
// desktop/gnome, desktop/kde). Above the seam the provider speaks of outputs,
// windows and pixels in *desktop coordinates*: the X11 root window's pixels,
// or a Wayland compositor's layout (logical pixels; the same as physical at
// scale 1). Document resolution (a process's files, the recent list) stays
// above it and works for every backend.
//
// Threads: the queries (outputs, window_at, capture, watch_new_window) are
// called from server threads and must be thread-safe; make_field_surface and
// everything a FieldSurface does run on the Qt thread.
#pragma once

#include <QImage>
#include <QPoint>
#include <QPointF>
#include <QString>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "provider/screen/screen_field.hpp"

class QScreen;
class QWindow;

namespace umf::provider {

// A rectangle in desktop coordinates.
struct WindowRect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
    bool contains(double px, double py) const;
    bool empty() const { return width <= 0 || height <= 0; }
    bool operator==(const WindowRect&) const = default;
};

// One monitor as the desktop lays it out.
struct DesktopOutput {
    std::string name;  // the connector, e.g. "DP-1", "HEADLESS-1"
    WindowRect rect;   // desktop coordinates
    double scale = 1.0;
    bool operator==(const DesktopOutput&) const = default;
};

struct WindowInfo {
    // The backend's handle: an X11 XID, a Sway container id, a Mutter
    // window id. Only meaningful to the backend that gave it.
    unsigned long id = 0;
    WindowRect rect;       // desktop coordinates, the frame included
    std::string title;     // UTF-8
    std::string instance;  // X11: WM_CLASS's instance; Wayland: empty
    std::string wm_class;  // X11: WM_CLASS's class; Wayland: the app id
    // The process that shows the window as the display server knows it;
    // 0 when unknown.
    int pid = 0;
    std::string output;  // the output it is mostly on; empty when unknown
};

// Windows that are not content: the provider's own (its PIDs), and classes
// of the caller's choosing (panels, a screen keyboard). Matching windows are
// looked through, as if absent.
struct WindowFilter {
    std::set<int> own_pids;
    std::set<std::string> skip_classes;  // matches instance or wm_class
    bool skips(const WindowInfo& window) const;
};

// Pixels of the screen, row-major, 0xffRRGGBB.
struct Capture {
    int width = 0;
    int height = 0;
    std::vector<std::uint32_t> pixels;
};

// A failure of the desktop to answer (a compositor that went away, a
// refused capture): the message says what, in words for the console.
class DesktopError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The field over one output: click-through (an empty input region from the
// first frame), above all windows, never focused. Shown only when asked.
// What OverlayManager needs of a window; the X11 one is a QRasterWindow
// (desktop/x11/overlay_window.hpp), the Wayland ones are a layer surface
// or a Shell actor.
class FieldSurface {
public:
    virtual ~FieldSurface() = default;
    virtual const ScreenField& screen_field() const = 0;
    // A new field or palette (the screen changed size or density).
    virtual void set_field(ScreenField field, const std::vector<std::string>& palette) = 0;
    // Follows the output's geometry.
    virtual void cover_screen() = 0;
    // 0..1, the pulse.
    virtual void set_opacity(double opacity) = 0;
    virtual double pulse_opacity() const = 0;
    // The most the pulse will reach (the preset's opacity_max): a surface
    // whose pulse is a cheap property (X11's window opacity) bakes it into
    // its pixels, so a compositor ignoring the property shows no more.
    virtual void set_pixel_opacity(double) {}
    // Only the field within `radius_px` of `centre_px` (the output's physical
    // pixels) is shown; nullopt shows all of it.
    virtual void set_focus(std::optional<QPointF> centre_px, double radius_px) = 0;
    // The painted pulse with a blurred backdrop (overlay_manager.hpp): a
    // backend that cannot paint it returns false from supports_painted_pulse
    // and is never asked.
    virtual bool supports_painted_pulse() const { return false; }
    virtual void set_painted_pulse(bool) {}
    virtual void set_backdrop(QImage, QPoint) {}
    // The ring and title where a phone points (screen/aim_mark.hpp), at
    // full strength whatever the pulse, for a surface that draws them itself
    // (on X11 they have a window of their own); nullopt removes them.
    virtual void set_aim_mark(std::optional<QPointF> /*point_px*/, const QString& /*title*/) {}
    virtual void show() = 0;
    virtual void hide() = 0;
    virtual bool is_visible() const = 0;
    // Put back above other windows (X11 override-redirect windows can be
    // covered by a restack; layer surfaces and actors stay on top).
    virtual void raise() {}
    // The same, but right under `sibling`, a window of the provider's that
    // belongs over the field (a put card), in one restack.
    virtual void raise_under(const QWindow& /*sibling*/) { raise(); }
};

// What a backend can do here, for the console and the tray.
struct DesktopAbilities {
    bool field = false;      // a click-through field over the outputs
    bool windows = false;    // the window at a point, with its process
    bool snapshots = false;  // the pixels of a window or region, without asking the person
    bool placement = false;  // moving a newly opened window to the pointed place
    // Sentences on what does not work here and why, with what to do.
    std::vector<std::string> notes;
};

// Where a put opens: the pointed place and its output, desktop coordinates.
struct WindowPlacement {
    double x = 0.0, y = 0.0;
    WindowRect screen;  // the output's rectangle
};

// One opening in progress (put/desktop_open.hpp): made before the opener
// starts, so it knows the windows that were there, then told its process.
class NewWindowWatch {
public:
    virtual ~NewWindowWatch() = default;
    // Watches for the child's window for up to `wait` and moves it centred on
    // the place (kept inside the output); the moved window's id, or nullopt.
    // Blocks: runs on a thread of its own.
    virtual std::optional<unsigned long> place(int child_pid, std::chrono::milliseconds wait) = 0;
};

class Desktop {
public:
    virtual ~Desktop() = default;
    // "x11", "wlroots", "kde", "gnome", "none".
    virtual std::string name() const = 0;
    virtual DesktopAbilities abilities() const = 0;

    // The outputs now; the bounding box of all of them is screen().
    virtual std::vector<DesktopOutput> outputs() const = 0;
    WindowRect screen() const;

    // The top-most shown window containing the point that the filter does
    // not skip; nullopt on the bare desktop or when windows cannot be known.
    virtual std::optional<WindowInfo> window_at(double x, double y, const WindowFilter& filter) const = 0;
    // Every shown window (X11: top-most first); empty where windows cannot be listed.
    virtual std::vector<WindowInfo> windows() const { return {}; }
    // The screen's pixels in `rect` as shown (the field hidden by the caller),
    // clipped to the desktop. Throws DesktopError.
    virtual Capture capture(const WindowRect& rect) const = 0;
    // nullptr when windows cannot be moved here.
    virtual std::unique_ptr<NewWindowWatch> watch_new_window(const WindowPlacement&) const { return nullptr; }

    // The field's surface over `screen` (Qt thread); nullptr when this
    // desktop cannot show one (abilities().field is false).
    virtual std::unique_ptr<FieldSurface> make_field_surface(QScreen* screen, ScreenField field,
                                                             const std::vector<std::string>& palette) = 0;

    // `changed` is called on the Qt thread when abilities() may answer
    // otherwise than before (an extension stopped or came back); one
    // listener, replaced by the next. Desktops whose abilities are fixed
    // once open never call it.
    virtual void on_abilities_changed(std::function<void()> /*changed*/) {}
};

}  // namespace umf::provider
