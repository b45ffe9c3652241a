#include "provider/desktop/kde/kwin_screenshot.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <QDBusArgument>
#include <QDBusMessage>
#include <QDBusMetaType>
#include <QDBusUnixFileDescriptor>
#include <QImage>

namespace umf::provider {

namespace {

// Reads until EOF, `want` bytes or the deadline.
QByteArray read_pipe(int fd, qsizetype want, std::chrono::steady_clock::time_point deadline) {
    QByteArray data;
    data.reserve(want);
    char buffer[65536];
    while (data.size() < want) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
        pollfd pfd{fd, POLLIN, 0};
        if (left <= 0 || ::poll(&pfd, 1, static_cast<int>(left)) <= 0) break;
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n <= 0) break;
        data.append(buffer, n);
    }
    return data;
}

}  // namespace

Capture capture_from_raw(const QVariantMap& layout, const QByteArray& data) {
    if (layout.value("type").toString() != "raw")
        throw DesktopError("KWin's screenshot is of type '" + layout.value("type").toString().toStdString() +
                           "', not raw");
    const int width = layout.value("width").toInt();
    const int height = layout.value("height").toInt();
    const int stride = layout.value("stride").toInt();
    const int format = layout.value("format").toInt();
    if (width <= 0 || height <= 0 || stride < width * 4 || format <= QImage::Format_Invalid ||
        format >= QImage::NImageFormats)
        throw DesktopError("KWin's screenshot has a layout umf does not read (format " + std::to_string(format) +
                           ", " + std::to_string(width) + "x" + std::to_string(height) + ", stride " +
                           std::to_string(stride) + ")");
    if (data.size() < static_cast<qsizetype>(stride) * height)
        throw DesktopError("KWin's screenshot ended after " + std::to_string(data.size()) + " of " +
                           std::to_string(static_cast<qsizetype>(stride) * height) + " bytes");
    const QImage image(reinterpret_cast<const uchar*>(data.constData()), width, height, stride,
                       static_cast<QImage::Format>(format));
    // Premultiplied or straight alpha, RGBA or ARGB byte orders: Qt brings
    // any of them to premultiplied ARGB, whose colour bits are the pixel
    // shown over black.
    const QImage rgb = image.convertToFormat(QImage::Format_ARGB32_Premultiplied);
    Capture capture{width, height, std::vector<std::uint32_t>(static_cast<std::size_t>(width) * height)};
    for (int y = 0; y < height; ++y) {
        const auto* line = reinterpret_cast<const std::uint32_t*>(rgb.constScanLine(y));
        for (int x = 0; x < width; ++x) capture.pixels[static_cast<std::size_t>(y) * width + x] = 0xff000000u | (line[x] & 0xffffffu);
    }
    return capture;
}

Capture kwin_capture_area(QDBusConnection& bus, const WindowRect& rect, std::chrono::milliseconds timeout) {
    if (rect.empty()) return {};
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw DesktopError("KDE: cannot make a pipe for the screenshot");
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    auto call = QDBusMessage::createMethodCall("org.kde.KWin.ScreenShot2", "/org/kde/KWin/ScreenShot2",
                                               "org.kde.KWin.ScreenShot2", "CaptureArea");
    QVariantMap options;
    options.insert("native-resolution", false);
    options.insert("include-cursor", false);
    call << rect.x << rect.y << static_cast<uint>(rect.width) << static_cast<uint>(rect.height) << options
         << QVariant::fromValue(QDBusUnixFileDescriptor(fds[1]));
    const QDBusMessage reply = bus.call(call, QDBus::Block, static_cast<int>(timeout.count()));
    // KWin has its own copy now: EOF comes when it is done writing.
    ::close(fds[1]);
    if (reply.type() != QDBusMessage::ReplyMessage || reply.arguments().isEmpty()) {
        ::close(fds[0]);
        const std::string why = reply.errorName().toStdString();
        if (why == "org.freedesktop.DBus.Error.ServiceUnknown" || why == "org.freedesktop.DBus.Error.UnknownObject")
            throw DesktopError("KWin offers no screenshot interface (org.kde.KWin.ScreenShot2: its screenshot effect "
                               "needs OpenGL compositing in KWin 5.27)");
        if (why == "org.kde.KWin.ScreenShot2.Error.NoAuthorized")
            throw DesktopError("KWin refused the screenshot: umf-provider's desktop file (with "
                               "X-KDE-DBUS-Restricted-Interfaces=org.kde.KWin.ScreenShot2) is not installed for "
                               "this executable (umf-provider kde install writes it)");
        throw DesktopError("KWin's screenshot failed (" + why + ": " + reply.errorMessage().toStdString() + ")");
    }
    const QVariantMap layout = qdbus_cast<QVariantMap>(reply.arguments().at(0));
    const qsizetype want = static_cast<qsizetype>(layout.value("stride").toInt()) * layout.value("height").toInt();
    const QByteArray data = read_pipe(fds[0], want, deadline);
    ::close(fds[0]);
    return capture_from_raw(layout, data);
}

}  // namespace umf::provider
