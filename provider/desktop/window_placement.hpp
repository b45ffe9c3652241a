// Where a put opens: the window xdg-open brings up for an accepted put
// (put/desktop_open.hpp) is moved so that it is centred on the place the
// phone pointed at, kept inside that screen. The rules every backend's
// NewWindowWatch (desktop.hpp) follows: the windows before the opener
// starts, then for up to kPlacementWaitMs a window that was not there,
// preferably one whose process descends from the opener (a browser that
// only opens a tab in an old window brings none, and nothing moves).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

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

}  // namespace umf::provider
