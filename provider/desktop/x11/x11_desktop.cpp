#include "provider/desktop/x11/x11_desktop.hpp"

#include "provider/desktop/x11/compositor.hpp"
#include "provider/desktop/x11/overlay_window.hpp"
#include "provider/desktop/x11/x11_pixels.hpp"
#include "provider/desktop/x11/x11_window_watch.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "shared/protocol/messages.hpp"

// After the project's headers: Xlib defines macros (None, Status, Bool).
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XRes.h>

namespace umf::provider {

namespace fs = std::filesystem;

namespace {

// Title bytes read at most: longer titles are clipped for display anyway.
constexpr long kMaxTitleLongs = 1024;
constexpr long kMaxListLongs = 65536;
constexpr int kWmStateIconic = 3;

// Xlib reports protocol errors (a window closed while we look at it gives
// BadWindow) to one handler per process, whose default exits the process.
// Errors on our connections are ignored, since every call's result tells of
// its failure; other connections' errors go to the handler that was there.
// A process-wide registry because Xlib's handler is process-wide.
class ErrorHandlerRegistry {
public:
    static ErrorHandlerRegistry& instance() {
        static ErrorHandlerRegistry registry;
        return registry;
    }
    void add(Display* display) {
        std::call_once(installed_, [this] { previous_.store(XSetErrorHandler(&ErrorHandlerRegistry::handle)); });
        std::lock_guard lock(mutex_);
        ours_.insert(display);
    }
    void remove(Display* display) {
        std::lock_guard lock(mutex_);
        if (const auto it = ours_.find(display); it != ours_.end()) ours_.erase(it);
    }

private:
    static int handle(Display* display, XErrorEvent* event) {
        auto& self = instance();
        {
            std::lock_guard lock(self.mutex_);
            if (self.ours_.count(display)) return 0;
        }
        const XErrorHandler previous = self.previous_.load();
        return previous ? previous(display, event) : 0;
    }

    std::once_flag installed_;
    std::atomic<XErrorHandler> previous_{nullptr};
    std::mutex mutex_;
    // A multiset: a closed display's address may come back for a new one
    // before the old one is removed.
    std::multiset<Display*> ours_;
};

struct XFreeDeleter {
    void operator()(void* data) const {
        if (data) XFree(data);
    }
};
template <class T>
using XPtr = std::unique_ptr<T, XFreeDeleter>;

struct ImageDeleter {
    void operator()(XImage* image) const {
        if (image) XDestroyImage(image);
    }
};

struct Atoms {
    Atom client_list_stacking, client_list, supporting_wm_check, wm_pid, wm_name, utf8_string, wm_state,
        net_wm_state, net_wm_state_hidden, frame_extents, window_type, window_type_desktop;
};

Atoms intern_atoms(Display* display) {
    std::array<const char*, 12> names{"_NET_CLIENT_LIST_STACKING",
                                      "_NET_CLIENT_LIST",
                                      "_NET_SUPPORTING_WM_CHECK",
                                      "_NET_WM_PID",
                                      "_NET_WM_NAME",
                                      "UTF8_STRING",
                                      "WM_STATE",
                                      "_NET_WM_STATE",
                                      "_NET_WM_STATE_HIDDEN",
                                      "_NET_FRAME_EXTENTS",
                                      "_NET_WM_WINDOW_TYPE",
                                      "_NET_WM_WINDOW_TYPE_DESKTOP"};
    std::array<Atom, 12> atoms{};
    if (!XInternAtoms(display, const_cast<char**>(names.data()), static_cast<int>(names.size()), False,
                      atoms.data()))
        throw std::runtime_error("X11: cannot intern the EWMH atoms");
    return {atoms[0], atoms[1], atoms[2], atoms[3], atoms[4], atoms[5],
            atoms[6], atoms[7], atoms[8], atoms[9], atoms[10], atoms[11]};
}

bool has_xres_client_ids(Display* display) {
    int event_base = 0, error_base = 0, major = 0, minor = 0;
    if (!XResQueryExtension(display, &event_base, &error_base)) return false;
    if (!XResQueryVersion(display, &major, &minor)) return false;
    return major > 1 || (major == 1 && minor >= 2);
}

std::string latin1_to_utf8(std::string_view text) {
    std::string out;
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x80) {
            out += c;
        } else {
            out += static_cast<char>(0xC0 | (byte >> 6));
            out += static_cast<char>(0x80 | (byte & 0x3F));
        }
    }
    return out;
}

std::string local_host_name() {
    std::array<char, 256> name{};
    if (::gethostname(name.data(), name.size() - 1) != 0) return {};
    return name.data();
}

}  // namespace

// The connection and what is asked of it; callers hold X11Desktop::mutex_.
struct X11Desktop::Connection {
    Display* display = nullptr;
    Window root = 0;
    Atoms atoms{};
    bool xres = false;
    std::string host = local_host_name();

    explicit Connection(const std::string& name) {
        display = XOpenDisplay(name.empty() ? nullptr : name.c_str());
        if (!display) {
            const char* env = std::getenv("DISPLAY");
            const std::string shown = !name.empty() ? name : env ? env : "";
            throw std::runtime_error("X11: cannot open the display '" + shown + "'" +
                                     (shown.empty() ? " (DISPLAY is not set)" : ""));
        }
        ErrorHandlerRegistry::instance().add(display);
        root = DefaultRootWindow(display);
        try {
            atoms = intern_atoms(display);
        } catch (...) {
            close();
            throw;
        }
        xres = has_xres_client_ids(display);
    }
    ~Connection() { close(); }
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    void close() {
        if (!display) return;
        XCloseDisplay(display);
        ErrorHandlerRegistry::instance().remove(display);
        display = nullptr;
    }

    // The property's items (format 32 comes as longs); nullopt when absent,
    // of another type (AnyPropertyType accepts all) or the window is gone.
    struct Property {
        Atom type = 0;
        int format = 0;
        unsigned long items = 0;
        XPtr<unsigned char> data;
    };
    std::optional<Property> property(Window window, Atom name, Atom type, long max_longs) const {
        Property p;
        unsigned long after = 0;
        unsigned char* data = nullptr;
        const int status = XGetWindowProperty(display, window, name, 0, max_longs, False, type, &p.type,
                                              &p.format, &p.items, &after, &data);
        p.data.reset(data);
        if (status != Success || p.type == 0 || !p.data) return std::nullopt;
        if (type != AnyPropertyType && p.type != type) return std::nullopt;
        return p;
    }

    // nullopt when absent, so an empty list can be told from none.
    std::optional<std::vector<unsigned long>> long_list(Window window, Atom name, Atom type,
                                                        long max_longs = kMaxListLongs) const {
        const auto p = property(window, name, type, max_longs);
        if (!p || p->format != 32) return std::nullopt;
        const auto* values = reinterpret_cast<const unsigned long*>(p->data.get());
        return std::vector<unsigned long>(values, values + p->items);
    }

    std::vector<unsigned long> longs(Window window, Atom name, Atom type, long max_longs = kMaxListLongs) const {
        return long_list(window, name, type, max_longs).value_or(std::vector<unsigned long>{});
    }

    std::optional<std::string> text(Window window, Atom name, Atom type) const {
        const auto p = property(window, name, type, kMaxTitleLongs);
        if (!p || p->format != 8) return std::nullopt;
        return std::string(reinterpret_cast<const char*>(p->data.get()), p->items);
    }

    // WM_NAME comes as Latin-1 (STRING), UTF-8 or COMPOUND_TEXT.
    std::string legacy_title(Window window) const {
        const auto p = property(window, XA_WM_NAME, AnyPropertyType, kMaxTitleLongs);
        if (!p || p->format != 8) return {};
        const std::string_view raw(reinterpret_cast<const char*>(p->data.get()), p->items);
        if (p->type == XA_STRING) return latin1_to_utf8(raw);
        if (p->type == atoms.utf8_string) return std::string(raw);
        XTextProperty property{p->data.get(), p->type, p->format, p->items};
        char** list = nullptr;
        int count = 0;
        if (Xutf8TextPropertyToTextList(display, &property, &list, &count) < Success || !list) return {};
        std::string title;
        for (int i = 0; i < count; ++i) title += list[i];
        XFreeStringList(list);
        return title;
    }

    std::string title(Window window) const {
        if (auto name = text(window, atoms.wm_name, atoms.utf8_string)) return *name;
        return legacy_title(window);
    }

    int pid(Window window) const {
        if (xres)
            if (const int found = x_server_client_pid(display, window); found > 0) return found;
        return claimed_pid(window);
    }

    // _NET_WM_PID is the client's own claim, and a PID only means something
    // on the client's host.
    int claimed_pid(Window window) const {
        const auto values = longs(window, atoms.wm_pid, XA_CARDINAL, 1);
        if (values.empty()) return 0;
        const auto machine = text(window, XA_WM_CLIENT_MACHINE, XA_STRING);
        if (machine && !machine->empty() && *machine != host) return 0;
        return static_cast<int>(values[0]);
    }

    void fill_class(Window window, WindowInfo& info) const {
        const auto value = text(window, XA_WM_CLASS, XA_STRING);
        if (!value) return;
        const std::size_t nul = value->find('\0');
        info.instance = value->substr(0, nul);
        if (nul != std::string::npos) info.wm_class = std::string(value->c_str() + nul + 1);
    }

    WindowInfo describe(Window window, const WindowRect& rect) const {
        WindowInfo info;
        info.id = window;
        info.rect = rect;
        info.title = title(window);
        fill_class(window, info);
        info.pid = pid(window);
        return info;
    }

    // Minimised (ICCCM or EWMH) or the desktop's background window.
    bool hidden(Window window) const {
        const auto state = longs(window, atoms.wm_state, atoms.wm_state, 2);
        if (!state.empty() && state[0] == kWmStateIconic) return true;
        const auto states = longs(window, atoms.net_wm_state, XA_ATOM);
        if (std::find(states.begin(), states.end(), atoms.net_wm_state_hidden) != states.end()) return true;
        const auto types = longs(window, atoms.window_type, XA_ATOM);
        return std::find(types.begin(), types.end(), atoms.window_type_desktop) != types.end();
    }

    // The client's rectangle in root coordinates with its border and the
    // window manager's frame; nullopt when it is not viewable.
    std::optional<WindowRect> client_rect(Window window) const {
        XWindowAttributes attributes{};
        if (!XGetWindowAttributes(display, window, &attributes) || attributes.map_state != IsViewable ||
            attributes.c_class == InputOnly)
            return std::nullopt;
        int x = 0, y = 0;
        Window child = 0;
        if (!XTranslateCoordinates(display, window, root, 0, 0, &x, &y, &child)) return std::nullopt;
        const int border = attributes.border_width;
        WindowRect rect{x - border, y - border, attributes.width + 2 * border, attributes.height + 2 * border};
        const auto extents = longs(window, atoms.frame_extents, XA_CARDINAL, 4);
        if (extents.size() == 4) {
            const auto [left, right, top, bottom] =
                std::array<int, 4>{static_cast<int>(extents[0]), static_cast<int>(extents[1]),
                                   static_cast<int>(extents[2]), static_cast<int>(extents[3])};
            rect = {rect.x - left, rect.y - top, rect.width + left + right, rect.height + top + bottom};
        }
        return rect;
    }

    // A top-level window without a window manager, or a frame's.
    std::optional<WindowRect> top_level_rect(Window window) const {
        XWindowAttributes attributes{};
        if (!XGetWindowAttributes(display, window, &attributes) || attributes.map_state != IsViewable ||
            attributes.c_class == InputOnly || attributes.override_redirect)
            return std::nullopt;
        const int border = attributes.border_width;
        return WindowRect{attributes.x, attributes.y, attributes.width + 2 * border,
                          attributes.height + 2 * border};
    }

    // EWMH's check: the root names a window that names itself, so a window
    // manager that died leaves no stale claim.
    bool wm_running() const {
        const auto check = longs(root, atoms.supporting_wm_check, XA_WINDOW, 1);
        if (check.empty() || check[0] == 0) return false;
        const auto self = longs(check[0], atoms.supporting_wm_check, XA_WINDOW, 1);
        return !self.empty() && self[0] == check[0];
    }

    std::vector<Window> children(Window window) const {
        Window root_return = 0, parent = 0;
        Window* list = nullptr;
        unsigned int count = 0;
        if (!XQueryTree(display, window, &root_return, &parent, &list, &count)) return {};
        XPtr<Window> owned(list);
        return {list, list + count};
    }

    // The window within a frame that carries WM_STATE (the client), searched
    // breadth first as xprop and xwininfo do; the frame itself without one.
    Window client_in(Window frame) const {
        std::deque<std::pair<Window, int>> queue{{frame, 0}};
        constexpr int kMaxDepth = 4;
        while (!queue.empty()) {
            const auto [window, depth] = queue.front();
            queue.pop_front();
            if (property(window, atoms.wm_state, atoms.wm_state, 2)) return window;
            if (depth < kMaxDepth)
                for (const Window child : children(window)) queue.emplace_back(child, depth + 1);
        }
        return frame;
    }

    // Client windows with their rectangles, top-most first.
    struct Candidate {
        Window client = 0;
        std::optional<WindowRect> rect;  // known up front for root children
    };
    std::vector<Candidate> stacking() const {
        std::vector<Candidate> candidates;
        if (wm_running()) {
            // _NET_CLIENT_LIST is in mapping order: a fallback for window
            // managers that keep no stacking list.
            auto clients = long_list(root, atoms.client_list_stacking, XA_WINDOW);
            if (!clients) clients = long_list(root, atoms.client_list, XA_WINDOW);
            if (clients) {
                for (auto it = clients->rbegin(); it != clients->rend(); ++it)
                    candidates.push_back({*it, std::nullopt});
                return candidates;
            }
        }
        const auto top_levels = children(root);
        for (auto it = top_levels.rbegin(); it != top_levels.rend(); ++it)
            if (auto rect = top_level_rect(*it)) candidates.push_back({client_in(*it), rect});
        return candidates;
    }

    std::optional<WindowRect> rect_of(const Candidate& candidate) const {
        return candidate.rect ? candidate.rect : client_rect(candidate.client);
    }

    Capture capture(const WindowRect& wanted) const {
        XWindowAttributes attributes{};
        if (!XGetWindowAttributes(display, root, &attributes))
            throw std::runtime_error("X11: cannot read the root window's size");
        const int x0 = std::max(wanted.x, 0), y0 = std::max(wanted.y, 0);
        const int x1 = std::min(wanted.x + wanted.width, attributes.width);
        const int y1 = std::min(wanted.y + wanted.height, attributes.height);
        if (x1 <= x0 || y1 <= y0) return {};
        std::unique_ptr<XImage, ImageDeleter> image(XGetImage(display, root, x0, y0, static_cast<unsigned>(x1 - x0),
                                                              static_cast<unsigned>(y1 - y0), AllPlanes, ZPixmap));
        if (!image) throw std::runtime_error("X11: the server refused to give the screen's pixels");
        return capture_from_ximage(*image, attributes.visual ? attributes.visual->c_class : -1);
    }
};

X11Desktop::X11Desktop(const std::string& display_name)
    : connection_(std::make_unique<Connection>(display_name)), display_name_(display_name) {}

X11Desktop::~X11Desktop() = default;

std::vector<DesktopOutput> X11Desktop::outputs() const {
    std::lock_guard lock(mutex_);
    XWindowAttributes attributes{};
    if (!XGetWindowAttributes(connection_->display, connection_->root, &attributes))
        throw DesktopError("X11: cannot read the root window's size");
    return {DesktopOutput{"root", {0, 0, attributes.width, attributes.height}, 1.0}};
}

DesktopAbilities X11Desktop::abilities() const {
    DesktopAbilities out;
    out.windows = true;
    out.snapshots = true;
    out.placement = has_ewmh();
    out.field = compositor_running(display_name_, 0);
    if (!out.field) out.notes.push_back(compositor_advice());
    if (!out.placement)
        out.notes.push_back("No EWMH window manager runs: an opened put's window stays where the program puts it.");
    return out;
}

std::unique_ptr<NewWindowWatch> X11Desktop::watch_new_window(const WindowPlacement& where) const {
    return X11NewWindowWatch::create(where, display_name_);
}

std::unique_ptr<FieldSurface> X11Desktop::make_field_surface(QScreen* screen, ScreenField field,
                                                            const std::vector<std::string>& palette) {
    return std::make_unique<OverlayWindow>(screen, std::move(field), palette);
}

bool X11Desktop::has_ewmh() const {
    std::lock_guard lock(mutex_);
    return connection_->wm_running();
}

std::vector<WindowInfo> X11Desktop::windows() const {
    std::lock_guard lock(mutex_);
    std::vector<WindowInfo> shown;
    for (const auto& candidate : connection_->stacking()) {
        const auto rect = connection_->rect_of(candidate);
        if (rect && !connection_->hidden(candidate.client))
            shown.push_back(connection_->describe(candidate.client, *rect));
    }
    return shown;
}

std::optional<WindowInfo> X11Desktop::window_at(double root_x, double root_y, const WindowFilter& filter) const {
    if (!std::isfinite(root_x) || !std::isfinite(root_y)) return std::nullopt;
    std::lock_guard lock(mutex_);
    // Cheapest test first: most windows do not contain the point.
    for (const auto& candidate : connection_->stacking()) {
        const auto rect = connection_->rect_of(candidate);
        if (!rect || !rect->contains(root_x, root_y) || connection_->hidden(candidate.client)) continue;
        WindowInfo info = connection_->describe(candidate.client, *rect);
        if (!filter.skips(info)) return info;
    }
    return std::nullopt;
}

Capture X11Desktop::capture(const WindowRect& rect) const {
    std::lock_guard lock(mutex_);
    return connection_->capture(rect);
}


int x_server_client_pid(Display* display, unsigned long window) {
    XResClientIdSpec spec{window, XRES_CLIENT_ID_PID_MASK};
    long count = 0;
    XResClientIdValue* values = nullptr;
    int found = 0;
    if (XResQueryClientIds(display, 1, &spec, &count, &values) == Success) {
        for (long i = 0; i < count && found <= 0; ++i)
            if (XResGetClientIdType(&values[i]) == XRES_CLIENT_ID_PID) found = XResGetClientPid(&values[i]);
        XResClientIdsDestroy(count, values);
    }
    return std::max(found, 0);
}

void ignore_x11_errors(Display* display) { ErrorHandlerRegistry::instance().add(display); }
void forget_x11_errors(Display* display) { ErrorHandlerRegistry::instance().remove(display); }

}  // namespace umf::provider
