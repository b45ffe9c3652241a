// The X11 NewWindowWatch (desktop/desktop.hpp, desktop/window_placement.hpp):
// the desktop's client list (_NET_CLIENT_LIST) is read before xdg-open
// starts, then watched for a window that was not there, preferably one whose
// _NET_WM_PID descends from the xdg-open child; it is moved with
// _NET_MOVERESIZE_WINDOW, and moved again while the window manager's own
// placement still takes it elsewhere. Without an X display, a window manager
// or a new window, nothing happens; a line on stderr says why when UMF_DEBUG
// is set.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/window_placement.hpp"

namespace umf::provider {

// Made before xdg-open starts (it reads the client list then), handed the
// child afterwards. Opening the display may fail (no X, no window manager):
// create gives nullptr then.
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
