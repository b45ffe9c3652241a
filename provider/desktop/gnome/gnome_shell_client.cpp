#include "provider/desktop/gnome/gnome_shell_client.hpp"

#include <QDBusArgument>
#include <QDBusConnection>
#include <QDBusConnectionInterface>
#include <QDBusMessage>
#include <QDBusMetaType>
#include <QDBusReply>
#include <QDBusServiceWatcher>
#include <QList>
#include <QStringList>
#include <QVariant>
#include <atomic>

#include "provider/desktop/gnome/gnome_extension.hpp"

namespace umf::provider {

namespace {

std::string text(const QString& s) { return s.toStdString(); }

WindowRect read_rect(const QDBusArgument& arg) {
    WindowRect r;
    arg.beginStructure();
    arg >> r.x >> r.y >> r.width >> r.height;
    arg.endStructure();
    return r;
}

// One (tisss(iiii)i), with the monitors' names for its index.
WindowInfo read_window(const QDBusArgument& arg, const std::vector<std::string>& monitor_names) {
    WindowInfo w;
    qulonglong id = 0;
    QString title, wm_class, instance;
    int monitor = -1;
    arg.beginStructure();
    arg >> id >> w.pid >> title >> wm_class >> instance;
    w.rect = read_rect(arg);
    arg >> monitor;
    arg.endStructure();
    w.id = static_cast<unsigned long>(id);
    w.title = text(title);
    w.wm_class = text(wm_class);
    w.instance = text(instance);
    if (monitor >= 0 && static_cast<std::size_t>(monitor) < monitor_names.size()) w.output = monitor_names[monitor];
    return w;
}

std::vector<std::string> names_of(const std::vector<DesktopOutput>& outputs) {
    std::vector<std::string> names;
    for (const auto& output : outputs) names.push_back(output.name);
    return names;
}

}  // namespace

class GnomeShellClient::Impl {
public:
    Impl(QString name, std::chrono::milliseconds timeout)
        : name_(std::move(name)),
          timeout_ms_(static_cast<int>(timeout.count())),
          bus_(connect(name_)) {}
    ~Impl() { QDBusConnection::disconnectFromBus(name_); }

    // The session bus named in the environment now (libdbus would keep the
    // first one it saw for the whole process).
    static QDBusConnection connect(const QString& name) {
        const QString address = qEnvironmentVariable("DBUS_SESSION_BUS_ADDRESS");
        return address.isEmpty() ? QDBusConnection::connectToBus(QDBusConnection::SessionBus, name)
                                 : QDBusConnection::connectToBus(address, name);
    }

    QDBusMessage message(const char* method, const QVariantList& args) const {
        auto m = QDBusMessage::createMethodCall(kGnomeShellBusName, kGnomeShellObjectPath, kGnomeShellInterface, method);
        m.setArguments(args);
        m.setAutoStartService(false);
        return m;
    }

    // The reply's arguments; DesktopError for an error or no answer in time.
    QList<QVariant> call(const char* method, const QVariantList& args = {}) const {
        const QDBusMessage reply = bus_.call(message(method, args), QDBus::Block, timeout_ms_);
        if (reply.type() == QDBusMessage::ReplyMessage) return reply.arguments();
        const QString error = reply.errorName();
        if (error == "org.freedesktop.DBus.Error.ServiceUnknown" || error == "org.freedesktop.DBus.Error.NameHasNoOwner")
            throw DesktopError("the umf GNOME Shell extension is not running (run: umf-provider gnome install, then log out and in)");
        if (error == "org.freedesktop.DBus.Error.NoReply" || error == "org.freedesktop.DBus.Error.Timeout")
            throw DesktopError("the umf GNOME Shell extension did not answer " + std::string(method) + " within " +
                               std::to_string(timeout_ms_) + " ms");
        throw DesktopError("the umf GNOME Shell extension: " + std::string(method) + ": " + text(reply.errorMessage()) +
                           " (" + text(error) + ")");
    }

    void send(const char* method, const QVariantList& args) const { bus_.send(message(method, args)); }

    QString name_;
    int timeout_ms_;
    QDBusConnection bus_;
};

GnomeShellClient::GnomeShellClient(std::chrono::milliseconds timeout) {
    static std::atomic<int> serial{0};
    impl_ = std::make_unique<Impl>(QString("umf-gnome-%1").arg(serial++), timeout);
    if (!impl_->bus_.isConnected()) {
        const std::string why = text(impl_->bus_.lastError().message());
        throw DesktopError("no session bus to reach GNOME Shell: " + why);
    }
}

GnomeShellClient::~GnomeShellClient() = default;

bool GnomeShellClient::extension_present() const {
    const auto reply = impl_->bus_.interface()->isServiceRegistered(kGnomeShellBusName);
    return reply.isValid() && reply.value();
}

std::unique_ptr<QObject> GnomeShellClient::watch_extension(std::function<void(bool running)> changed) const {
    auto watcher = std::make_unique<QDBusServiceWatcher>(kGnomeShellBusName, impl_->bus_,
                                                         QDBusServiceWatcher::WatchForOwnerChange);
    QObject::connect(watcher.get(), &QDBusServiceWatcher::serviceOwnerChanged, watcher.get(),
                     [changed = std::move(changed)](const QString&, const QString&, const QString& owner) {
                         changed(!owner.isEmpty());
                     });
    return watcher;
}

GnomeShellVersion GnomeShellClient::version() const {
    const auto out = impl_->call("Version");
    if (out.size() != 2) throw DesktopError("the umf GNOME Shell extension gave a malformed Version");
    return {out[0].toUInt(), text(out[1].toString())};
}

std::vector<DesktopOutput> GnomeShellClient::monitors() const {
    const auto out = impl_->call("Monitors");
    if (out.size() != 1) throw DesktopError("the umf GNOME Shell extension gave malformed Monitors");
    const auto arg = out[0].value<QDBusArgument>();
    std::vector<DesktopOutput> monitors;
    arg.beginArray();
    while (!arg.atEnd()) {
        DesktopOutput m;
        QString name;
        arg.beginStructure();
        arg >> name >> m.rect.x >> m.rect.y >> m.rect.width >> m.rect.height >> m.scale;
        arg.endStructure();
        m.name = text(name);
        monitors.push_back(std::move(m));
    }
    arg.endArray();
    return monitors;
}

std::optional<WindowInfo> GnomeShellClient::window_at(double x, double y, const WindowFilter& filter) const {
    QList<int> pids(filter.own_pids.begin(), filter.own_pids.end());
    QStringList classes;
    for (const auto& c : filter.skip_classes) classes << QString::fromStdString(c);
    const auto out = impl_->call("WindowAt", {x, y, QVariant::fromValue(pids), classes});
    if (out.size() != 2) throw DesktopError("the umf GNOME Shell extension gave a malformed WindowAt");
    if (!out[0].toBool()) return std::nullopt;
    // The monitor's name costs a second call only when a window was found.
    return read_window(out[1].value<QDBusArgument>(), names_of(monitors()));
}

std::vector<WindowInfo> GnomeShellClient::windows() const {
    const auto out = impl_->call("ListWindows");
    if (out.size() != 1) throw DesktopError("the umf GNOME Shell extension gave a malformed ListWindows");
    const auto names = names_of(monitors());
    const auto arg = out[0].value<QDBusArgument>();
    std::vector<WindowInfo> windows;
    arg.beginArray();
    while (!arg.atEnd()) windows.push_back(read_window(arg, names));
    arg.endArray();
    return windows;
}

bool GnomeShellClient::move_window(unsigned long id, int x, int y) const {
    const auto out = impl_->call("MoveWindow", {QVariant::fromValue(qulonglong(id)), x, y});
    return out.size() == 1 && out[0].toBool();
}

std::string GnomeShellClient::snapshot(const WindowRect& rect) const { return shot("Snapshot", rect); }

std::string GnomeShellClient::screen_as_shown(const WindowRect& rect) const { return shot("ScreenAsShown", rect); }

std::string GnomeShellClient::shot(const char* method, const WindowRect& rect) const {
    const auto out = impl_->call(method, {rect.x, rect.y, rect.width, rect.height});
    if (out.size() != 1) throw DesktopError(std::string("the umf GNOME Shell extension gave a malformed ") + method);
    return text(out[0].toString());
}

void GnomeShellClient::set_field(int monitor, const std::string& file_name) const {
    impl_->call("SetField", {monitor, QString::fromStdString(file_name)});
}

void GnomeShellClient::drop_field(int monitor) const { impl_->send("DropField", {monitor}); }

std::vector<GnomeFieldState> GnomeShellClient::field_state() const {
    const auto out = impl_->call("FieldState");
    if (out.size() != 1) throw DesktopError("the umf GNOME Shell extension gave a malformed FieldState");
    const auto arg = out[0].value<QDBusArgument>();
    std::vector<GnomeFieldState> fields;
    arg.beginArray();
    while (!arg.atEnd()) {
        GnomeFieldState f;
        uint opacity = 0;
        arg.beginStructure();
        arg >> f.monitor >> f.visible >> opacity >> f.focus;
        f.rect = read_rect(arg);
        arg.beginStructure();
        arg >> f.image_width >> f.image_height;
        arg.endStructure();
        arg.endStructure();
        f.opacity = opacity;
        fields.push_back(f);
    }
    arg.endArray();
    return fields;
}

void GnomeShellClient::send_field_opacity(int monitor, double opacity) const {
    impl_->send("SetFieldOpacity", {monitor, opacity});
}

void GnomeShellClient::send_field_focus(int monitor, std::optional<std::pair<double, double>> centre, double radius) const {
    impl_->send("SetFieldFocus", {monitor, centre.has_value(), centre ? centre->first : 0.0,
                                  centre ? centre->second : 0.0, radius});
}

void GnomeShellClient::send_field_visible(int monitor, bool visible) const {
    impl_->send("SetFieldVisible", {monitor, visible});
}

void GnomeShellClient::send_aim_mark(int monitor, const std::string& file_name, double x, double y) const {
    impl_->send("SetAimMark", {monitor, QString::fromStdString(file_name), x, y});
}

void GnomeShellClient::send_drop_aim_mark(int monitor) const { impl_->send("DropAimMark", {monitor}); }

}  // namespace umf::provider
