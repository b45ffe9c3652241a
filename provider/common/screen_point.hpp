// A place on the provider's screens, as resolvers, puts and the overlay's
// activity name it.
#pragma once

namespace umf::provider {

// A point on one of the provider's screens, in that screen's pixels
// (continuous: pixel (x, y) covers [x, x + 1) x [y, y + 1)); `screen` indexes
// the welcome's screens. On X11 the screens' pixels are the root window's,
// offset by the screen's position (ScreenPoint::root_x/root_y).
struct ScreenPoint {
    int screen = 0;
    double x = 0.0;
    double y = 0.0;
    // The same point in the X11 root window's coordinates (desktop mode).
    double root_x = 0.0;
    double root_y = 0.0;
};

}  // namespace umf::provider
