// Snapshots through KWin's screenshot D-Bus interface:
// org.kde.KWin.ScreenShot2 on /org/kde/KWin/ScreenShot2 (service
// org.kde.KWin.ScreenShot2), CaptureArea(x, y, w, h, options, pipe) writes
// the raw image to the pipe and tells its layout in the reply (type "raw",
// format as a QImage::Format number, width, height, stride).
//
// KWin lets only some callers use it: it reads the caller's executable
// (/proc/PID/exe of the bus name's process) and looks for an installed
// application .desktop file whose Exec= is exactly that path (no
// arguments) and which names org.kde.KWin.ScreenShot2 in
// X-KDE-DBUS-Restricted-Interfaces; others get
// org.kde.KWin.ScreenShot2.Error.NoAuthorized. The provider's desktop entry
// (desktop/desktop_entry.hpp) is such a file. The interface lives in KWin's screenshot effect,
// which KWin 5.27 loads only with OpenGL compositing (not with QPainter, as
// on a machine without a GPU).
#pragma once

#include <QDBusConnection>
#include <QVariantMap>
#include <chrono>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// The image KWin wrote, as the seam's Capture. Throws DesktopError for a
// layout it does not know or data that is too short.
Capture capture_from_raw(const QVariantMap& layout, const QByteArray& data);

// The area's pixels as shown. Throws DesktopError (no screenshot interface,
// refused, timed out).
Capture kwin_capture_area(QDBusConnection& bus, const WindowRect& rect, std::chrono::milliseconds timeout);

}  // namespace umf::provider
