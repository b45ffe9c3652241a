// A pointer of the test's own in a GNOME session: mutter's RemoteDesktop
// D-Bus API, which makes a virtual input device in the compositor's seat, so
// its events are picked, focused and delivered as a real mouse's would be
// (unlike XTest on Xwayland, which never leaves the X server).
//
// Mutter ties a remote-desktop session to the bus connection that made it:
// only that connection may call it, and the session closes when it goes. So
// one QtDBus connection holds it for the helper's life; a gdbus per call
// would lose the session between calls.
//
// Only relative motion is used: absolute motion needs a screen-cast stream
// (and PipeWire) to name its coordinate space. The pointer is first pushed
// far past the bottom-right corner, where mutter clamps it to the last pixel,
// so the relative step after it lands on a known place. Not the top-left
// corner: that is GNOME's hot corner, and the overview it opens would take
// the click.
#pragma once

#include <QDBusConnection>
#include <QDBusMessage>
#include <QDBusObjectPath>
#include <QString>
#include <QVariant>
#include <atomic>
#include <stdexcept>
#include <string>

namespace umf::test {

class MutterRemoteDesktop {
public:
    static constexpr int kLeftButton = 272;  // BTN_LEFT of linux/input-event-codes.h

    // Connects to the session bus at `bus_address` (as whoever the effective
    // user is meanwhile) and starts a remote-desktop session. Throws
    // std::runtime_error with mutter's error when it refuses.
    explicit MutterRemoteDesktop(const std::string& bus_address)
        : name_(QStringLiteral("umf-test-remote-desktop-%1").arg(next_id())),
          bus_(QDBusConnection::connectToBus(QString::fromStdString(bus_address), name_)) {
        if (!bus_.isConnected()) {
            const std::string why = bus_.lastError().message().toStdString();
            QDBusConnection::disconnectFromBus(name_);
            throw std::runtime_error("cannot connect to the session bus: " + why);
        }
        try {
            const QDBusMessage created = call(QStringLiteral("/org/gnome/Mutter/RemoteDesktop"),
                                              QStringLiteral("org.gnome.Mutter.RemoteDesktop"),
                                              QStringLiteral("CreateSession"), {});
            session_ = created.arguments().value(0).value<QDBusObjectPath>().path();
            if (session_.isEmpty()) throw std::runtime_error("CreateSession gave no session path");
            session_call(QStringLiteral("Start"), {});
            started_ = true;
        } catch (...) {
            QDBusConnection::disconnectFromBus(name_);
            throw;
        }
    }

    ~MutterRemoteDesktop() {
        // Stop releases the virtual devices at once; the disconnect would
        // too, a moment later.
        if (started_) {
            try {
                session_call(QStringLiteral("Stop"), {});
            } catch (const std::exception&) {
            }
        }
        QDBusConnection::disconnectFromBus(name_);
    }
    MutterRemoteDesktop(const MutterRemoteDesktop&) = delete;
    MutterRemoteDesktop& operator=(const MutterRemoteDesktop&) = delete;

    void move_by(double dx, double dy) {
        session_call(QStringLiteral("NotifyPointerMotionRelative"), {dx, dy});
    }

    // To (x, y) in desktop (logical) pixels of a desktop `width` x `height`
    // (one monitor at the origin), by way of its bottom-right pixel.
    void move_to(double x, double y, int width, int height) {
        move_by(100000, 100000);
        move_by(x - (width - 1), y - (height - 1));
    }

    void button(int code, bool pressed) {
        session_call(QStringLiteral("NotifyPointerButton"), {code, pressed});
    }

    void click(int code = kLeftButton) {
        button(code, true);
        button(code, false);
    }

private:
    static int next_id() {
        static std::atomic<int> id{0};
        return ++id;
    }

    // Blocking, bounded by the timeout; each call also orders the events,
    // since mutter handles one connection's calls in turn.
    QDBusMessage call(const QString& path, const QString& interface, const QString& method, const QVariantList& args) {
        auto message = QDBusMessage::createMethodCall(QStringLiteral("org.gnome.Mutter.RemoteDesktop"), path, interface,
                                                      method);
        message.setArguments(args);
        message.setAutoStartService(false);
        const QDBusMessage reply = bus_.call(message, QDBus::Block, 5000);
        if (reply.type() != QDBusMessage::ReplyMessage)
            throw std::runtime_error(method.toStdString() + ": " + reply.errorName().toStdString() + ": " +
                                     reply.errorMessage().toStdString());
        return reply;
    }
    QDBusMessage session_call(const QString& method, const QVariantList& args) {
        return call(session_, QStringLiteral("org.gnome.Mutter.RemoteDesktop.Session"), method, args);
    }

    QString name_;
    QDBusConnection bus_;
    QString session_;
    bool started_ = false;
};

}  // namespace umf::test
