#include "provider/desktop/x11/x11_window_watch.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <set>
#include <thread>

#include "provider/desktop/x11/x11_desktop.hpp"

// Last: Xlib's macros clash with the standard library's and Qt's names.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/extensions/XRes.h>

namespace umf::provider {

namespace {

void debug_line(const std::string& text) {
    if (const char* debug = std::getenv("UMF_DEBUG"); debug && *debug)
        std::cerr << "umf-provider: put window: " << text << "\n";
}

}  // namespace

struct X11NewWindowWatch::Connection {
    Display* display = nullptr;
    Window root = 0;
    Atom client_list = 0, wm_pid = 0, supported = 0, moveresize = 0, frame_extents = 0, window_type = 0,
         type_normal = 0, type_dialog = 0;

    explicit Connection(Display* d) : display(d), root(DefaultRootWindow(d)) {
        ignore_x11_errors(display);
        client_list = XInternAtom(display, "_NET_CLIENT_LIST", False);
        wm_pid = XInternAtom(display, "_NET_WM_PID", False);
        supported = XInternAtom(display, "_NET_SUPPORTED", False);
        moveresize = XInternAtom(display, "_NET_MOVERESIZE_WINDOW", False);
        frame_extents = XInternAtom(display, "_NET_FRAME_EXTENTS", False);
        window_type = XInternAtom(display, "_NET_WM_WINDOW_TYPE", False);
        type_normal = XInternAtom(display, "_NET_WM_WINDOW_TYPE_NORMAL", False);
        type_dialog = XInternAtom(display, "_NET_WM_WINDOW_TYPE_DIALOG", False);
    }
    ~Connection() {
        XCloseDisplay(display);
        forget_x11_errors(display);
    }
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    // A format-32 property's items; nullopt when absent (or the window is gone).
    std::optional<std::vector<unsigned long>> longs(Window window, Atom name, Atom type) const {
        Atom actual = 0;
        int format = 0;
        unsigned long items = 0, after = 0;
        unsigned char* data = nullptr;
        const int status =
            XGetWindowProperty(display, window, name, 0, 65536, False, type, &actual, &format, &items, &after, &data);
        std::optional<std::vector<unsigned long>> out;
        // An empty list (no clients yet) may come without data.
        if (status == Success && format == 32 && actual != None) {
            const auto* values = reinterpret_cast<const unsigned long*>(data);
            out.emplace();
            if (values) out->assign(values, values + items);
        }
        if (data) XFree(data);
        return out;
    }

    std::vector<unsigned long> clients() const { return longs(root, client_list, XA_WINDOW).value_or(std::vector<unsigned long>{}); }

    // The X server's word for a local client first; _NET_WM_PID is the
    // client's own claim.
    std::optional<int> pid(Window window) const {
        int event_base = 0, error_base = 0;
        if (XResQueryExtension(display, &event_base, &error_base))
            if (const int found = x_server_client_pid(display, window); found > 0) return found;
        const auto p = longs(window, wm_pid, XA_CARDINAL);
        if (!p || p->empty()) return std::nullopt;
        return static_cast<int>((*p)[0]);
    }

    // A plain application window that no other opening of the provider's
    // brought up: one that descends from the provider but not from this
    // opening's child is another put's (or the provider's own).
    bool normal(Window window) const {
        if (const auto p = pid(window); p && descends_from(*p, static_cast<int>(::getpid()))) return false;
        const auto types = longs(window, window_type, XA_ATOM);
        if (!types || types->empty()) return true;  // no type: a normal window (EWMH)
        return std::any_of(types->begin(), types->end(),
                           [&](unsigned long t) { return t == type_normal || t == type_dialog; });
    }

    bool supports(Atom atom) const {
        const auto list = longs(root, supported, XA_ATOM);
        return list && std::find(list->begin(), list->end(), atom) != list->end();
    }

    // Where `window`'s frame should go for the whole to be centred on the
    // place, and where its frame's corner is now (root coordinates); nullopt
    // when the window is gone. The frame's extents are read each time: a
    // window manager may set them only after it lists the window.
    struct Spot {
        PlaceRect to;
        int x = 0, y = 0;
    };
    std::optional<Spot> spot(Window window, const WindowPlacement& where) const {
        XWindowAttributes attributes;
        if (!XGetWindowAttributes(display, window, &attributes)) return std::nullopt;
        int x = 0, y = 0;
        Window child = 0;
        if (!XTranslateCoordinates(display, window, root, 0, 0, &x, &y, &child)) return std::nullopt;
        std::array<long, 4> extents{0, 0, 0, 0};  // left, right, top, bottom
        if (const auto e = longs(window, frame_extents, XA_CARDINAL); e && e->size() == 4)
            for (std::size_t i = 0; i < 4; ++i) extents[i] = static_cast<long>((*e)[i]);
        const int border = attributes.border_width;
        const int width = attributes.width + 2 * border + static_cast<int>(extents[0] + extents[1]);
        const int height = attributes.height + 2 * border + static_cast<int>(extents[2] + extents[3]);
        const PlaceRect to = centred_on(width, height, where.x, where.y, where.screen);
        return Spot{to, x - border - static_cast<int>(extents[0]), y - border - static_cast<int>(extents[2])};
    }

    // Asks for `window`'s frame to go to `to`'s corner.
    void move(Window window, const PlaceRect& to) const {
        if (supports(moveresize)) {
            // Gravity north-west: x and y are the frame's corner. Source 2:
            // a pager, whose moves the window manager carries out.
            XEvent event{};
            event.xclient.type = ClientMessage;
            event.xclient.window = window;
            event.xclient.message_type = moveresize;
            event.xclient.format = 32;
            event.xclient.data.l[0] = NorthWestGravity | (1 << 8) | (1 << 9) | (2 << 12);
            event.xclient.data.l[1] = to.x;
            event.xclient.data.l[2] = to.y;
            XSendEvent(display, root, False, SubstructureRedirectMask | SubstructureNotifyMask, &event);
        } else {
            XMoveWindow(display, window, to.x, to.y);
        }
        XSync(display, False);
        debug_line("moved window " + std::to_string(window) + " to " + std::to_string(to.x) + "," +
                   std::to_string(to.y));
    }

    // Moves `window` to the place and stays with it until its frame has been
    // there for a few looks: a window manager may still apply its own
    // placement (or learn its frame's size) after it lists a new window, and
    // a move asked for before that is lost. False when the window is gone.
    bool settle(Window window, const WindowPlacement& where) const {
        constexpr int kLooks = 15, kMoves = 5, kSteady = 3;
        int moves = 0, steady = 0;
        for (int look = 0; look < kLooks && steady < kSteady; ++look) {
            const auto now = spot(window, where);
            if (!now) return look > 0;
            if (std::abs(now->x - now->to.x) <= 1 && std::abs(now->y - now->to.y) <= 1) {
                ++steady;
            } else if (moves < kMoves) {
                steady = 0;
                move(window, now->to);
                ++moves;
            } else {
                debug_line("window " + std::to_string(window) + " does not stay where it was moved");
                return true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        return true;
    }
};

std::unique_ptr<X11NewWindowWatch> X11NewWindowWatch::create(WindowPlacement where, const std::string& display_name) {
    const char* env = std::getenv("DISPLAY");
    if (display_name.empty() && (!env || !*env)) {
        debug_line("no X display, so the opened window stays where it opens");
        return nullptr;
    }
    Display* display = XOpenDisplay(display_name.empty() ? nullptr : display_name.c_str());
    if (!display) {
        debug_line("cannot open the X display");
        return nullptr;
    }
    auto connection = std::make_unique<Connection>(display);
    // A window manager that speaks EWMH; its client list may still be unset
    // (no clients yet, or it has only just started).
    const Atom check = XInternAtom(display, "_NET_SUPPORTING_WM_CHECK", False);
    const auto wm = connection->longs(connection->root, check, XA_WINDOW);
    if (!wm || wm->empty()) {
        debug_line("no window manager to list the windows (_NET_SUPPORTING_WM_CHECK)");
        return nullptr;
    }
    return std::unique_ptr<X11NewWindowWatch>(new X11NewWindowWatch(std::move(connection), where));
}

X11NewWindowWatch::X11NewWindowWatch(std::unique_ptr<Connection> connection, WindowPlacement where)
    : connection_(std::move(connection)), where_(where), before_(connection_->clients()) {}

X11NewWindowWatch::~X11NewWindowWatch() = default;

std::optional<unsigned long> X11NewWindowWatch::place(int child_pid, std::chrono::milliseconds wait) {
    const auto deadline = std::chrono::steady_clock::now() + wait;
    const Connection& c = *connection_;
    const auto from_child = [&](unsigned long w) {
        const auto pid = c.pid(w);
        return pid && descends_from(*pid, child_pid);
    };
    const auto normal = [&](unsigned long w) { return c.normal(w); };
    while (true) {
        if (const auto window = pick_new_window(before_, c.clients(), from_child, normal)) {
            if (c.settle(*window, where_)) return window;
            before_.push_back(*window);  // gone already: another may come
        }
        if (std::chrono::steady_clock::now() >= deadline) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    debug_line("no new window within " + std::to_string(wait.count()) + " ms");
    return std::nullopt;
}

}  // namespace umf::provider
