#include "provider/discovery/avahi_announcement.hpp"

#include <QDBusConnection>
#include <QDBusInterface>
#include <QDBusMetaType>
#include <QDBusObjectPath>
#include <QDBusReply>
#include <QList>
#include <chrono>

namespace umf::provider {

namespace {

// Avahi's D-Bus interface (avahi-daemon's org.freedesktop.Avahi.Server and
// .EntryGroup; the numbers are avahi-common's).
constexpr const char* kAvahi = "org.freedesktop.Avahi";
constexpr const char* kServer = "org.freedesktop.Avahi.Server";
constexpr const char* kEntryGroup = "org.freedesktop.Avahi.EntryGroup";
constexpr int kAnyInterface = -1, kAnyProtocol = -1;
constexpr int kGroupEstablished = 2, kGroupCollision = 3, kGroupFailure = 4;
// A call to a daemon that is not there may start a D-Bus activation: never
// wait on it for long.
constexpr int kCallTimeoutMs = 3000;

QString text(const std::string& s) { return QString::fromStdString(s); }

QList<QByteArray> txt_records(const std::vector<std::string>& txt) {
    QList<QByteArray> out;
    for (const auto& t : txt) out.push_back(QByteArray::fromStdString(t));
    return out;
}

// One of the entry group's states after a commit: established, collision
// or failure (polled: the provider runs no event loop of its own here).
int wait_for_group(QDBusInterface& group, const bool& stopping, std::mutex& mutex) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
        {
            std::lock_guard lock(mutex);
            if (stopping) return kGroupFailure;
        }
        const QDBusReply<int> state = group.call("GetState");
        if (!state.isValid()) return kGroupFailure;
        if (state.value() >= kGroupEstablished) return state.value();
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return kGroupFailure;
}

}  // namespace

AvahiAnnouncement::AvahiAnnouncement(Announcement wanted,
                                     std::function<void(const Announcement&, const std::string&)> done)
    : thread_([this, wanted = std::move(wanted), done = std::move(done)] { run(wanted, done); }) {}

AvahiAnnouncement::~AvahiAnnouncement() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    thread_.join();
    if (!group_.empty()) {
        QDBusInterface group(kAvahi, text(group_), kEntryGroup, QDBusConnection::systemBus());
        group.setTimeout(kCallTimeoutMs);
        group.call("Free");
    }
}

void AvahiAnnouncement::run(Announcement wanted,
                            const std::function<void(const Announcement&, const std::string&)>& done) {
    qDBusRegisterMetaType<QList<QByteArray>>();
    QDBusConnection bus = QDBusConnection::systemBus();
    if (!bus.isConnected()) return done({}, "there is no system D-Bus");
    QDBusInterface server(kAvahi, "/", kServer, bus);
    server.setTimeout(kCallTimeoutMs);
    const QDBusReply<QString> host = server.call("GetHostNameFqdn");
    if (!host.isValid()) return done({}, "the Avahi daemon does not answer (" + host.error().message().toStdString() + ")");
    const QDBusReply<QDBusObjectPath> path = server.call("EntryGroupNew");
    if (!path.isValid()) return done({}, "Avahi refused an entry group: " + path.error().message().toStdString());
    {
        std::lock_guard lock(mutex_);
        group_ = path.value().path().toStdString();
    }
    QDBusInterface group(kAvahi, path.value().path(), kEntryGroup, bus);
    group.setTimeout(kCallTimeoutMs);
    Announcement made = wanted;
    made.host_name = host.value().toStdString();
    for (int attempt = 1; attempt <= 9; ++attempt) {
        made.instance = attempt == 1 ? wanted.instance : wanted.instance + " (" + std::to_string(attempt) + ")";
        group.call("Reset");
        const QDBusMessage added =
            group.call("AddService", kAnyInterface, kAnyProtocol, 0u, text(made.instance), text(native::kScreenServiceType),
                       QString(), QString(), QVariant::fromValue<quint16>(made.port),
                       QVariant::fromValue(txt_records(made.txt)));
        if (added.type() == QDBusMessage::ErrorMessage) {
            if (added.errorName() == "org.freedesktop.Avahi.CollisionError") continue;
            return done({}, "Avahi refused the service: " + added.errorMessage().toStdString());
        }
        const QDBusMessage committed = group.call("Commit");
        if (committed.type() == QDBusMessage::ErrorMessage)
            return done({}, "Avahi refused the service: " + committed.errorMessage().toStdString());
        const int state = wait_for_group(group, stopping_, mutex_);
        if (state == kGroupEstablished) return done(made, {});
        if (state != kGroupCollision) return done({}, "Avahi could not announce the service");
    }
    done({}, "every name tried is taken on the network");
}

}  // namespace umf::provider
