// Running a KWin script and taking its answer: the script is written into a
// private folder (0700) of the provider's, loaded with
// org.kde.kwin.Scripting.loadScript, started with org.kde.kwin.Script.run
// (on /Scripting/ScriptN in KWin 6, /N in KWin 5.27) and unloaded after.
// It answers by callDBus to an object of the provider's on the same bus,
// which wakes the waiting caller; an answer whose sender does not own
// org.kde.KWin is ignored. Every wait has a timeout, so a KWin that is gone
// or stuck gives an error, never a hang.
//
// Threads: run() may be called from any thread (calls are serialised);
// answers are received on a thread of the runner's own.
#pragma once

#include <QDBusConnection>
#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

class QThread;

namespace umf::provider {

class KWinAnswerSink;

// The session bus, or the bus at `address` (tests run their own).
QDBusConnection kde_bus_connection(const std::string& address);

class KWinScripting {
public:
    // Throws DesktopError when the bus cannot be reached or the answer
    // object cannot be registered.
    KWinScripting(QDBusConnection bus, std::filesystem::path script_dir);
    ~KWinScripting();
    KWinScripting(const KWinScripting&) = delete;
    KWinScripting& operator=(const KWinScripting&) = delete;

    // Runs `body`, which calls umfAnswer(text) once, and returns the text.
    // Throws DesktopError (KWin absent, the script refused, no answer within
    // `timeout`).
    std::string run(const std::string& body, std::chrono::milliseconds timeout) const;

    // The unique bus name owning org.kde.KWin, or empty.
    std::string kwin_owner() const;

private:
    std::string start_script(const std::string& plugin, const std::string& path, std::chrono::milliseconds timeout) const;

    mutable QDBusConnection bus_;
    std::filesystem::path script_dir_;
    std::unique_ptr<QThread> thread_;
    KWinAnswerSink* sink_ = nullptr;  // lives on thread_
    mutable std::mutex mutex_;
    mutable unsigned long next_ = 0;
    // Which object path style this KWin uses: 0 unknown, 6 or 5.
    mutable int script_path_style_ = 0;
};

}  // namespace umf::provider
