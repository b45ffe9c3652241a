#include "provider/desktop/kde/kwin_scripting.hpp"

#include <unistd.h>

#include <QDBusConnectionInterface>
#include <QDBusMessage>
#include <QDBusVirtualObject>
#include <QThread>
#include <atomic>
#include <condition_variable>
#include <fstream>
#include <map>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/kde/kwin_scripts.hpp"

namespace umf::provider {

namespace {

constexpr const char* kKWinService = "org.kde.KWin";
constexpr const char* kAnswerPath = "/org/umf/KWinAnswer";
constexpr const char* kAnswerInterface = "org.umf.KWinAnswer";

std::string text_of(const QDBusMessage& reply) {
    return reply.errorName().toStdString() + ": " + reply.errorMessage().toStdString();
}

}  // namespace

// Receives Answer(token, text) calls; a waiter is woken by its token.
class KWinAnswerSink final : public QDBusVirtualObject {
public:
    struct Waiter {
        std::string expected_sender;
        std::optional<std::string> answer;
    };

    bool handleMessage(const QDBusMessage& message, const QDBusConnection& connection) override {
        if (message.interface() != kAnswerInterface || message.member() != "Answer" ||
            message.arguments().size() != 2)
            return false;
        const std::string token = message.arguments().at(0).toString().toStdString();
        {
            std::lock_guard lock(mutex_);
            const auto it = waiters_.find(token);
            if (it != waiters_.end() && it->second.expected_sender == message.service().toStdString()) {
                it->second.answer = message.arguments().at(1).toString().toStdString();
                answered_.notify_all();
            }
        }
        connection.send(message.createReply());
        return true;
    }

    QString introspect(const QString&) const override {
        return QStringLiteral("<interface name=\"org.umf.KWinAnswer\"><method name=\"Answer\">"
                              "<arg name=\"token\" type=\"s\" direction=\"in\"/>"
                              "<arg name=\"text\" type=\"s\" direction=\"in\"/></method></interface>");
    }

    void expect(const std::string& token, const std::string& sender) {
        std::lock_guard lock(mutex_);
        waiters_[token] = {sender, std::nullopt};
    }
    std::optional<std::string> wait(const std::string& token, std::chrono::steady_clock::time_point deadline) {
        std::unique_lock lock(mutex_);
        answered_.wait_until(lock, deadline, [&] { return waiters_[token].answer.has_value(); });
        auto answer = std::move(waiters_[token].answer);
        waiters_.erase(token);
        return answer;
    }

private:
    std::mutex mutex_;
    std::condition_variable answered_;
    std::map<std::string, Waiter> waiters_;
};

// A connection of the backend's own, also to the session bus: on Qt's
// shared session-bus connection the scripts' answers were handled on the
// main thread, which the window probe blocks while it waits for one, so
// every provider started in a KWin session timed out its probe and ran
// without windows (KdeProvider.*).
QDBusConnection kde_bus_connection(const std::string& address) {
    static std::atomic<int> count{0};
    const QString name = QStringLiteral("umf-kde-%1").arg(count.fetch_add(1));
    if (address.empty()) return QDBusConnection::connectToBus(QDBusConnection::SessionBus, name);
    return QDBusConnection::connectToBus(QString::fromStdString(address), name);
}

KWinScripting::KWinScripting(QDBusConnection bus, std::filesystem::path script_dir)
    : bus_(std::move(bus)), script_dir_(std::move(script_dir)) {
    if (!bus_.isConnected())
        throw DesktopError("KDE: the session bus cannot be reached (" + bus_.lastError().message().toStdString() + ")");
    thread_ = std::make_unique<QThread>();
    thread_->setObjectName(QStringLiteral("umf kwin answers"));
    thread_->start();
    sink_ = new KWinAnswerSink;
    sink_->moveToThread(thread_.get());
    if (!bus_.registerVirtualObject(kAnswerPath, sink_, QDBusConnection::SingleNode)) {
        thread_->quit();
        thread_->wait();
        delete sink_;
        throw DesktopError("KDE: cannot register the provider's answer object on the session bus");
    }
}

KWinScripting::~KWinScripting() {
    bus_.unregisterObject(kAnswerPath);
    thread_->quit();
    thread_->wait();
    delete sink_;
}

std::string KWinScripting::kwin_owner() const {
    const auto reply = bus_.interface()->serviceOwner(kKWinService);
    return reply.isValid() ? reply.value().toStdString() : std::string();
}

std::string KWinScripting::start_script(const std::string& plugin, const std::string& path,
                                        std::chrono::milliseconds timeout) const {
    auto load = QDBusMessage::createMethodCall(kKWinService, "/Scripting", "org.kde.kwin.Scripting", "loadScript");
    load << QString::fromStdString(path) << QString::fromStdString(plugin);
    const QDBusMessage loaded = bus_.call(load, QDBus::Block, static_cast<int>(timeout.count()));
    if (loaded.type() != QDBusMessage::ReplyMessage || loaded.arguments().isEmpty())
        throw DesktopError("KWin did not load the provider's script (" + text_of(loaded) + ")");
    const int id = loaded.arguments().at(0).toInt();
    if (id < 0) throw DesktopError("KWin refused the provider's script " + path);
    // KWin 6 names a script /Scripting/ScriptN, KWin 5.27 /N.
    for (const int style : {6, 5}) {
        if (script_path_style_ != 0 && script_path_style_ != style) continue;
        const QString object = style == 6 ? QStringLiteral("/Scripting/Script%1").arg(id) : QStringLiteral("/%1").arg(id);
        auto run = QDBusMessage::createMethodCall(kKWinService, object, "org.kde.kwin.Script", "run");
        const QDBusMessage ran = bus_.call(run, QDBus::Block, static_cast<int>(timeout.count()));
        if (ran.type() == QDBusMessage::ReplyMessage) {
            script_path_style_ = style;
            return {};
        }
        if (ran.errorName() != "org.freedesktop.DBus.Error.UnknownObject" &&
            ran.errorName() != "org.freedesktop.DBus.Error.UnknownMethod")
            return "KWin did not run the provider's script (" + text_of(ran) + ")";
    }
    return "KWin offers no org.kde.kwin.Script object for the provider's script";
}

std::string KWinScripting::run(const std::string& body, std::chrono::milliseconds timeout) const {
    std::lock_guard lock(mutex_);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    const std::string owner = kwin_owner();
    if (owner.empty()) throw DesktopError("KWin is not on the session bus (no owner of org.kde.KWin)");
    const std::string token = std::to_string(::getpid()) + "-" + std::to_string(++next_);
    const std::string plugin = "umf-provider-" + token;
    const std::filesystem::path path = script_dir_ / (plugin + ".js");
    {
        std::ofstream out(path, std::ios::trunc);
        out << "function umfAnswer(text) {\n    callDBus(" << js_string(bus_.baseService().toStdString()) << ", "
            << js_string(kAnswerPath) << ", " << js_string(kAnswerInterface) << ", \"Answer\", "
            << js_string(token) << ", String(text));\n}\n"
            << body;
        if (!out) throw DesktopError("cannot write the KWin script " + path.string());
    }
    sink_->expect(token, owner);
    auto unload = QDBusMessage::createMethodCall(kKWinService, "/Scripting", "org.kde.kwin.Scripting", "unloadScript");
    unload << QString::fromStdString(plugin);
    std::string failure;
    try {
        failure = start_script(plugin, path.string(), timeout);
    } catch (...) {
        sink_->wait(token, std::chrono::steady_clock::now());
        // A stuck KWin may still load it later: the unload queued behind
        // the load takes it away again, unanswered.
        bus_.send(unload);
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
        throw;
    }
    const auto answer = failure.empty() ? sink_->wait(token, deadline) : sink_->wait(token, std::chrono::steady_clock::now());
    if (answer)
        bus_.call(unload, QDBus::Block, static_cast<int>(timeout.count()));
    else
        bus_.send(unload);
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    if (!failure.empty()) throw DesktopError(failure);
    if (!answer) throw DesktopError("KWin's script did not answer within " + std::to_string(timeout.count()) + " ms");
    return *answer;
}

}  // namespace umf::provider
