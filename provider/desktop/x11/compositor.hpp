// Whether a compositing manager runs on an X screen: without one an ARGB
// window is drawn opaque and _NET_WM_WINDOW_OPACITY is ignored, so the
// overlay would hide the desktop instead of tinting it. Xlib stays out of
// this header (its macros clash with Qt).
#pragma once

#include <string>

typedef struct _XDisplay Display;

namespace umf::provider {

// By the owner of the _NET_WM_CM_S<screen> selection (EWMH, "Compositing
// managers"), which a compositing manager holds while it runs.
bool compositor_running(Display* display, int screen);
// Opens the display (an empty name means $DISPLAY) for the question; false
// when it cannot be opened.
bool compositor_running(const std::string& display_name, int screen);

// What the user can do when none runs, in a sentence or two.
std::string compositor_advice();

}  // namespace umf::provider
