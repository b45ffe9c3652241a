#include "provider/desktop/x11/compositor.hpp"

#include <X11/Xlib.h>

#include <memory>

namespace umf::provider {

bool compositor_running(Display* display, int screen) {
    if (!display) return false;
    const std::string name = "_NET_WM_CM_S" + std::to_string(screen);
    // only_if_exists: no compositor ever ran when the atom is unknown.
    const Atom selection = XInternAtom(display, name.c_str(), True);
    return selection != None && XGetSelectionOwner(display, selection) != None;
}

bool compositor_running(const std::string& display_name, int screen) {
    const std::unique_ptr<Display, int (*)(Display*)> display(
        XOpenDisplay(display_name.empty() ? nullptr : display_name.c_str()), XCloseDisplay);
    return compositor_running(display.get(), screen);
}

std::string compositor_advice() {
    return "No compositing manager runs, so the field cannot be mixed into the screen. Start one such as picom "
           "(apt install picom; picom &) or enable compositing in your window manager's settings. On Wayland "
           "run the provider with QT_QPA_PLATFORM=xcb (XWayland).";
}

}  // namespace umf::provider
