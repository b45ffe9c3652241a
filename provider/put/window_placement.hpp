// Where a put opens: the window xdg-open brings up for an accepted put
// (desktop_open.hpp) is moved so that it is centred on the place the phone
// pointed at, kept inside that screen. Best effort and X11 only: the
// desktop's client list (_NET_CLIENT_LIST) is read before xdg-open starts,
// then watched for up to kPlacementWaitMs for a window that was not there,
// preferably one whose _NET_WM_PID descends from the xdg-open child (a
// browser that only opens a tab in an old window brings none, and nothing
// moves). Without an X display, a window manager or a new window, nothing
// happens; a line on stderr says why when UMF_DEBUG is set.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "desktop/desktop.hpp"

namespace umf::provider {

inline constexpr int kPlacementWaitMs = 5000;

using PlaceRect = WindowRect;

// Where a window of outer size `width` x `height` goes so that its centre is
// on (x, y), moved the least needed to lie inside `screen` (its top-left
// corner kept on the screen when it is larger than the screen).
PlaceRect centred_on(int width, int height, double x, double y, const PlaceRect& screen);

// The window to move among the client list `now`: the first one not in
// `before` that `from_child` accepts, else the first new one that `normal`
// accepts (a plain application window, not a dock or a splash, not one that
// another opening brought up), else none.
std::optional<unsigned long> pick_new_window(const std::vector<unsigned long>& before,
                                             const std::vector<unsigned long>& now,
                                             const std::function<bool(unsigned long)>& from_child,
                                             const std::function<bool(unsigned long)>& normal);

// Whether process `pid` is `ancestor` or descends from it (/proc/PID/stat's
// parent chain); false once a process on the way has gone.
bool descends_from(int pid, int ancestor);

// The watch for one opening: made before xdg-open starts (it reads the
// client list then), handed the child afterwards. Opening the display may
// fail (no X, no window manager): create gives nullptr then.
class X11NewWindowWatch final : public NewWindowWatch {
public:
    // `display_name` empty: $DISPLAY.
    static std::unique_ptr<X11NewWindowWatch> create(WindowPlacement where, const std::string& display_name = {});
    ~X11NewWindowWatch() override;
    X11NewWindowWatch(const X11NewWindowWatch&) = delete;
    X11NewWindowWatch& operator=(const X11NewWindowWatch&) = delete;

    // Watches for the child's window for up to `wait` and moves it; the id
    // of the window moved, or nullopt. Blocks: desktop_open runs it on a
    // thread of its own.
    std::optional<unsigned long> place(int child_pid,
                                       std::chrono::milliseconds wait = std::chrono::milliseconds(kPlacementWaitMs)) override;

private:
    struct Connection;
    X11NewWindowWatch(std::unique_ptr<Connection> connection, WindowPlacement where);

    std::unique_ptr<Connection> connection_;
    WindowPlacement where_;
    std::vector<unsigned long> before_;
};

}  // namespace umf::provider
