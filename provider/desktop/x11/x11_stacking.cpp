#include "provider/desktop/x11/x11_stacking.hpp"

#include <QGuiApplication>
#include <QWindow>

// Last: Xlib's macros clash with Qt's headers.
#include <X11/Xlib.h>

namespace umf::provider {

void stack_under(QWindow& window, const QWindow& sibling) {
    if (QGuiApplication::platformName() != QLatin1String("xcb")) return;
    const auto* x11 = qGuiApp->nativeInterface<QNativeInterface::QX11Application>();
    Display* display = x11 ? x11->display() : nullptr;
    if (!display || &window == &sibling) return;
    XWindowChanges changes{};
    changes.sibling = static_cast<::Window>(sibling.winId());
    changes.stack_mode = Below;
    XConfigureWindow(display, static_cast<::Window>(window.winId()), CWSibling | CWStackMode, &changes);
    // Qt's xcb plugin would hold the request until its next X event.
    XFlush(display);
}

}  // namespace umf::provider
