// A KWin of the test's own: kwin_wayland --virtual (no GPU: QPainter
// compositing) with Xwayland, on a private session bus (dbus-daemon) and a
// private XDG_RUNTIME_DIR and config. KWin runs as the test's user (it does
// not refuse root).
//
// Debian gives /usr/bin/kwin_wayland the file capability cap_sys_resource
// (for real-time scheduling); in a container whose bounding set lacks it,
// exec fails with EPERM. The test runs a copy without the capability,
// which also keeps "kwin_wayland" as the program's name (KWin's own Qt
// platform plugin checks it).
#pragma once

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::test {

struct KWinSession {
    std::unique_ptr<TempDir> dir;
    fs::path runtime;
    std::string bus_address;
    std::string wayland_display = "umf-kwin-test";
    std::string x_display;  // KWin's Xwayland
    std::unique_ptr<Process> bus;
    std::unique_ptr<Process> kwin;

    // The session's environment, for its clients.
    std::vector<std::string> env(const std::map<std::string, std::string>& more = {}) const {
        std::map<std::string, std::string> vars{{"XDG_RUNTIME_DIR", runtime.string()},
                                                {"DBUS_SESSION_BUS_ADDRESS", bus_address},
                                                {"WAYLAND_DISPLAY", wayland_display},
                                                {"DISPLAY", x_display},
                                                {"XDG_SESSION_TYPE", "wayland"},
                                                {"XDG_CURRENT_DESKTOP", "KDE"},
                                                {"XDG_CONFIG_HOME", (dir->path / "config").string()},
                                                {"QT_QPA_PLATFORM", "wayland"}};
        for (const auto& [k, v] : more) vars[k] = v;
        return environment_with(vars);
    }
    std::string log() const {
        std::ifstream in(dir->path / "kwin.log");
        return {std::istreambuf_iterator<char>(in), {}};
    }
};

// The X display of the Xwayland that process `parent` started, or empty.
inline std::string xwayland_display_of(pid_t parent) {
    for (const auto& entry : fs::directory_iterator("/proc")) {
        std::ifstream stat(entry.path() / "stat");
        std::string pid, comm, state;
        long ppid = 0;
        if (!(stat >> pid >> comm >> state >> ppid) || ppid != parent || comm != "(Xwayland)") continue;
        std::ifstream cmdline(entry.path() / "cmdline");
        std::string program, display;
        std::getline(cmdline, program, '\0');
        std::getline(cmdline, display, '\0');
        if (!display.empty() && display[0] == ':') return display;
    }
    return {};
}

// Why KWin cannot run here, or nullopt when it can be tried.
inline std::optional<std::string> kwin_missing() {
    for (const char* program : {"kwin_wayland", "dbus-daemon", "Xwayland", "gdbus"})
        if (!find_program(program))
            return std::string(program) + " is not installed (Debian: apt-get install -y kwin-wayland dbus xwayland "
                                          "libglib2.0-bin)";
    return std::nullopt;
}

// Throws std::runtime_error (with KWin's log) when it does not come up.
inline KWinSession start_kwin(int width = 1920, int height = 1080) {
    KWinSession s;
    s.dir = std::make_unique<TempDir>("umf-kwin");
    s.runtime = s.dir->path / "runtime";
    fs::create_directories(s.runtime);
    fs::create_directories(s.dir->path / "config");
    ::chmod(s.runtime.c_str(), 0700);
    s.bus_address = "unix:path=" + (s.dir->path / "bus").string();

    Process::Options options;
    options.log = s.dir->path / "dbus.log";
    s.bus = std::make_unique<Process>(
        std::vector<std::string>{"dbus-daemon", "--session", "--nofork", "--address=" + s.bus_address}, options);
    if (!wait_until([&] { return fs::exists(s.dir->path / "bus"); }, 10s))
        throw std::runtime_error("dbus-daemon did not start");

    const fs::path kwin = s.dir->path / "kwin_wayland";
    fs::copy_file(*find_program("kwin_wayland"), kwin);  // without the file capability, see above
    ::chmod(kwin.c_str(), 0755);
    auto env = s.env({{"KWIN_COMPOSE", "Q"}});
    std::erase_if(env, [](const std::string& e) { return e.rfind("QT_QPA_PLATFORM=", 0) == 0 || e.rfind("DISPLAY=", 0) == 0; });
    options.env = env;
    options.log = s.dir->path / "kwin.log";
    s.kwin = std::make_unique<Process>(
        std::vector<std::string>{kwin.string(), "--virtual", "--xwayland", "--width", std::to_string(width), "--height",
                                 std::to_string(height), "--socket", s.wayland_display},
        options);
    const auto has_kwin = [&] {
        try {
            return run({"gdbus", "call", "--session", "-d", "org.freedesktop.DBus", "-o", "/org/freedesktop/DBus", "-m",
                        "org.freedesktop.DBus.NameHasOwner", "org.kde.KWin"},
                       s.env(), 5s)
                       .find("true") != std::string::npos;
        } catch (const std::exception&) {
            return false;
        }
    };
    if (!wait_until([&] { return fs::exists(s.runtime / s.wayland_display) && has_kwin(); }, 30s))
        throw std::runtime_error("kwin_wayland did not start:\n" + s.log());
    if (!wait_until([&] { return !(s.x_display = xwayland_display_of(s.kwin->pid())).empty(); }, 20s))
        throw std::runtime_error("kwin_wayland started no Xwayland:\n" + s.log());
    const fs::path socket = "/tmp/.X11-unix/X" + s.x_display.substr(1);
    if (!wait_until([&] { return fs::exists(socket); }, 10s)) throw std::runtime_error("Xwayland made no socket");
    return s;
}

}  // namespace umf::test
