// A KWin of the test's own: kwin_wayland --virtual with Xwayland, on a
// private session bus (dbus-daemon) and a private XDG_RUNTIME_DIR, config,
// data and cache. KWin runs as the test's user (it does not refuse root).
// It composites with QPainter, or with OpenGL on Mesa's software renderer
// (llvmpipe; KWinOptions::opengl), as a desktop with a GPU does: only then
// does KWin 5.27 load its screenshot effect (org.kde.KWin.ScreenShot2).
// KWin finds the applications it lets use that interface in the session's
// data folder (`applications` below `data`; install_application).
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

struct KWinOptions {
    int width = 1920;
    int height = 1080;
    bool opengl = false;
};

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
                                                {"XDG_DATA_HOME", data_home().string()},
                                                {"XDG_CACHE_HOME", (dir->path / "cache").string()},
                                                {"QT_QPA_PLATFORM", "wayland"}};
        for (const auto& [k, v] : more) vars[k] = v;
        return environment_with(vars);
    }
    fs::path data_home() const { return dir->path / "data"; }
    // A client in the session's environment, its output in `log` in the
    // session's folder.
    std::unique_ptr<Process> start_client(const std::vector<std::string>& argv, const std::string& log) const {
        Process::Options options;
        options.env = env();
        options.log = dir->path / log;
        return std::make_unique<Process>(argv, options);
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

// An application entry in the session's data folder, as a package installs
// one, for the program at `executable` (the first word of Exec=, which
// KWin compares with a client's /proc/PID/exe), granting it KWin's
// restricted D-Bus interfaces and Wayland interfaces named (comma
// separated). KWin reads the folder within seconds, even while it runs.
inline void install_application(const KWinSession& s, const std::string& id, const fs::path& executable,
                                const std::string& restricted_interfaces, const std::string& wayland_interfaces = "") {
    const fs::path applications = s.data_home() / "applications";
    fs::create_directories(applications);
    std::ofstream entry(applications / (id + ".desktop"));
    entry << "[Desktop Entry]\nType=Application\nName=" << id << "\nExec=" << fs::canonical(executable).string()
          << "\nNoDisplay=true\nX-KDE-DBUS-Restricted-Interfaces=" << restricted_interfaces << "\n";
    if (!wayland_interfaces.empty()) entry << "X-KDE-Wayland-Interfaces=" << wayland_interfaces << "\n";
}

// A folder of the session made before KWin starts, so that what the test
// puts there (install_application) is there when KWin first looks.
inline KWinSession prepare_kwin_session() {
    KWinSession s;
    s.dir = std::make_unique<TempDir>("umf-kwin");
    s.runtime = s.dir->path / "runtime";
    fs::create_directories(s.runtime);
    for (const char* sub : {"config", "data", "cache"}) fs::create_directories(s.dir->path / sub);
    ::chmod(s.runtime.c_str(), 0700);
    s.bus_address = "unix:path=" + (s.dir->path / "bus").string();
    return s;
}

// Starts KWin in a prepared session. Throws std::runtime_error (with KWin's
// log) when it does not come up.
inline KWinSession start_kwin(KWinSession s, const KWinOptions& kwin_options = {}) {
    Process::Options options;
    options.log = s.dir->path / "dbus.log";
    s.bus = std::make_unique<Process>(
        std::vector<std::string>{"dbus-daemon", "--session", "--nofork", "--address=" + s.bus_address}, options);
    if (!wait_until([&] { return fs::exists(s.dir->path / "bus"); }, 10s))
        throw std::runtime_error("dbus-daemon did not start");

    const fs::path kwin = s.dir->path / "kwin_wayland";
    fs::copy_file(*find_program("kwin_wayland"), kwin);  // without the file capability, see above
    ::chmod(kwin.c_str(), 0755);
    // Software OpenGL for the compositing: Mesa's llvmpipe, whatever GPU
    // the machine has or lacks.
    auto env = kwin_options.opengl ? s.env({{"KWIN_COMPOSE", "O2"}, {"LIBGL_ALWAYS_SOFTWARE", "1"}})
                                   : s.env({{"KWIN_COMPOSE", "Q"}});
    std::erase_if(env, [](const std::string& e) { return e.rfind("QT_QPA_PLATFORM=", 0) == 0 || e.rfind("DISPLAY=", 0) == 0; });
    options.env = env;
    options.log = s.dir->path / "kwin.log";
    s.kwin = std::make_unique<Process>(
        std::vector<std::string>{kwin.string(), "--virtual", "--xwayland", "--width", std::to_string(kwin_options.width),
                                 "--height", std::to_string(kwin_options.height), "--socket", s.wayland_display},
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

inline KWinSession start_kwin(const KWinOptions& options = {}) { return start_kwin(prepare_kwin_session(), options); }

}  // namespace umf::test
