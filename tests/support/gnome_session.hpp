// A GNOME Shell 43 of the test's own: headless, on a virtual monitor, run as
// an unprivileged user (the shell, like sway, is not for root) with its own
// runtime folder and home, a private system bus (the shell asks it for
// logind and friends) and a session bus that also lets root connect, so a
// test can call as a foreign user. The umf extension is installed and
// enabled in that home before the shell starts.
#pragma once

#include <grp.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>

#include "provider/desktop/gnome/gnome_install.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::test {

inline constexpr const char* kGnomeTestUser = "umf-gnome-test";

// The effective user switched for a scope: connections made and files
// written meanwhile are the user's. Root stays the real and saved user, so
// the switch back is allowed.
class AsUser {
public:
    AsUser(uid_t uid, gid_t gid) {
        if (::setegid(gid) != 0 || ::seteuid(uid) != 0) throw std::runtime_error("cannot become the test user");
    }
    ~AsUser() {
        // A test left running as the user would write root's files as the
        // user's, or fail far from here: stop at once instead.
        if (::seteuid(0) != 0 || ::setegid(0) != 0) {
            std::perror("cannot become root again after running as the test user");
            std::abort();
        }
    }
    AsUser(const AsUser&) = delete;
    AsUser& operator=(const AsUser&) = delete;
};

struct GnomeSessionOptions {
    bool install_extension = true;
    bool enable_extension = true;
};

class GnomeSession {
public:
    using Options = GnomeSessionOptions;

    // Why a GNOME Shell cannot run here, or nullopt.
    static std::optional<std::string> unavailable() {
        if (::geteuid() != 0) return "the GNOME Shell tests make a user and switch to it: they need root";
        for (const char* program : {"gnome-shell", "dbus-run-session", "dbus-daemon", "setpriv", "gsettings"})
            if (!find_program(program)) return std::string(program) + " is not installed";
        return std::nullopt;
    }

    explicit GnomeSession(const Options& options = {}) : root_("umf-gnome") {
        ensure_user();
        ensure_x11_socket_folder();
        run_ = root_.path / "run";
        home_ = root_.path / "home";
        fs::create_directories(run_);
        fs::create_directories(home_ / ".local/share/gnome-shell/extensions");
        ::chmod(root_.path.c_str(), 0755);
        ::chmod(run_.c_str(), 0700);
        write_file(root_.path / "system.conf", system_bus_config());
        write_file(root_.path / "session.conf", session_bus_config());
        std::string enable = "gsettings set org.gnome.shell disable-user-extensions false\n";
        if (options.enable_extension)
            enable += "gsettings set org.gnome.shell enabled-extensions \"['" UMF_GNOME_EXTENSION_UUID "']\"\n";
        write_file(root_.path / "shell.sh",
                   "#!/bin/sh\necho \"$DBUS_SESSION_BUS_ADDRESS\" > \"$XDG_RUNTIME_DIR/bus-address\"\n" + enable +
                       "exec gnome-shell --headless --wayland --virtual-monitor 1920x1080\n");
        ::chmod((root_.path / "shell.sh").c_str(), 0755);
        if (options.install_extension) install_extension();
        chown_all(root_.path);

        system_bus_ = std::make_unique<Process>(
            as_user({"dbus-daemon", "--nofork", "--config-file=" + (root_.path / "system.conf").string()}),
            options_with_log("system-bus.log"));
        wait_for_path(run_ / "system_bus", 5s, "the private system bus");
        shell_ = std::make_unique<Process>(
            as_user({"dbus-run-session", "--config-file=" + (root_.path / "session.conf").string(), "--",
                     (root_.path / "shell.sh").string()}),
            options_with_log("shell.log"));
        wait_for_path(run_ / "bus-address", 10s, "the session bus");
        wait_for_path(run_ / "wayland-0", 20s, "gnome-shell's Wayland socket");
        std::ifstream address(run_ / "bus-address");
        std::getline(address, bus_address_);
    }

    const fs::path& run_dir() const { return run_; }
    const fs::path& home() const { return home_; }
    const std::string& bus_address() const { return bus_address_; }
    uid_t uid() const { return uid_; }
    gid_t gid() const { return gid_; }
    std::string log() const { return read_file(root_.path / "shell.log"); }

    // The environment the user's programs see in this session.
    std::vector<std::string> client_env(const std::map<std::string, std::string>& more = {}) const {
        std::map<std::string, std::string> env = {
            {"PATH", "/usr/bin:/bin"},        {"HOME", home_.string()},
            {"XDG_RUNTIME_DIR", run_.string()}, {"WAYLAND_DISPLAY", "wayland-0"},
            {"DBUS_SESSION_BUS_ADDRESS", bus_address_}, {"LANG", "C.UTF-8"}};
        for (const auto& [k, v] : more) env[k] = v;
        std::vector<std::string> out;
        for (const auto& [k, v] : env) out.push_back(k + "=" + v);
        return out;
    }

    // A program run as the session's user.
    std::unique_ptr<Process> start_client(const std::vector<std::string>& argv, const std::string& log_name,
                                          const std::map<std::string, std::string>& env = {}) const {
        Process::Options o = options_with_log(log_name);
        o.env = client_env(env);
        return std::make_unique<Process>(as_user(argv), o);
    }

    // A short command run as the session's user, its stdout; throws when it
    // fails or outlasts the timeout. Call it as root: setpriv needs root to
    // become the user.
    std::string run_client(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env = {},
                           Clock::duration timeout = 5s) const {
        return run(as_user(argv), client_env(env), timeout);
    }

    // Leaves the overview GNOME 43 starts in (org.gnome.Shell's
    // OverviewActive), so windows are where their frames say.
    bool leave_overview(Clock::duration timeout = 10s) const {
        const auto call = [&](const std::string& method, const std::vector<std::string>& args) {
            std::vector<std::string> argv = {"gdbus", "call", "--session", "-d", "org.gnome.Shell", "-o",
                                             "/org/gnome/Shell", "-m", method};
            argv.insert(argv.end(), args.begin(), args.end());
            try {
                return run(as_user(argv), client_env(), 5s);
            } catch (const std::exception&) {
                return std::string();
            }
        };
        // The shell may show it again once its start-up ends: it must stay
        // down a while.
        int down = 0;
        return wait_until([&] {
            call("org.freedesktop.DBus.Properties.Set", {"org.gnome.Shell", "OverviewActive", "<false>"});
            std::this_thread::sleep_for(200ms);
            down = call("org.freedesktop.DBus.Properties.Get", {"org.gnome.Shell", "OverviewActive"}).find("false") !=
                           std::string::npos
                       ? down + 1
                       : 0;
            return down >= 5;
        }, timeout);
    }

    // Xwayland's display and its cookie file, from its command line (it
    // runs as this session's user; mutter starts it at startup).
    std::optional<std::pair<std::string, std::string>> xwayland() const {
        for (const auto& entry : fs::directory_iterator("/proc")) {
            struct stat info {};
            if (::stat(entry.path().c_str(), &info) != 0 || info.st_uid != uid_) continue;
            std::string cmd = read_file(entry.path() / "cmdline");
            std::replace(cmd.begin(), cmd.end(), '\0', ' ');
            std::smatch m;
            if (cmd.find("Xwayland") != std::string::npos && cmd.find(run_.string()) != std::string::npos &&
                std::regex_search(cmd, m, std::regex(R"(Xwayland (:[0-9]+) .*-auth (\S+))")))
                return std::pair{m[1].str(), m[2].str()};
        }
        return std::nullopt;
    }

    pid_t shell_pid() const {
        // dbus-run-session's child that runs gnome-shell (shell.sh execs it).
        for (const auto& entry : fs::directory_iterator("/proc")) {
            struct stat info {};
            if (::stat(entry.path().c_str(), &info) != 0 || info.st_uid != uid_) continue;
            const std::string cmd = read_file(entry.path() / "cmdline");
            if (cmd.rfind("gnome-shell", 0) == 0 && cmd.find("--headless") != std::string::npos &&
                read_file(entry.path() / "environ").find(run_.string()) != std::string::npos)
                return std::stoi(entry.path().filename().string());
        }
        return 0;
    }

private:
    static std::string read_file(const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
    static void write_file(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

    // The shell starts Xwayland and refuses a /tmp/.X11-unix that is not
    // root's and open to all (1777), as a booted system makes it. On a
    // machine whose /tmp holds none yet (a fresh container, or a run of the
    // GNOME tests alone, before any Xvfb test made it) the shell would make
    // it itself, as the test user, and stop.
    static void ensure_x11_socket_folder() {
        const fs::path folder = "/tmp/.X11-unix";
        std::error_code ignored;
        fs::create_directory(folder, ignored);
        struct stat st {};
        if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
            throw std::runtime_error(folder.string() + " is not a folder");
        if ((st.st_uid != 0 && ::chown(folder.c_str(), 0, 0) != 0) ||
            ((st.st_mode & 07777) != 01777 && ::chmod(folder.c_str(), 01777) != 0))
            throw std::runtime_error("cannot make " + folder.string() + " root's and open to all (1777): " +
                                     std::strerror(errno));
    }

    void ensure_user() {
        if (!::getpwnam(kGnomeTestUser))
            run({"useradd", "--system", "--create-home", kGnomeTestUser}, environment_with({}), 30s);
        const passwd* user = ::getpwnam(kGnomeTestUser);
        if (!user) throw std::runtime_error("no user " + std::string(kGnomeTestUser));
        uid_ = user->pw_uid;
        gid_ = user->pw_gid;
    }

    std::vector<std::string> as_user(std::vector<std::string> argv) const {
        std::vector<std::string> out = {"setpriv", "--reuid=" + std::to_string(uid_), "--regid=" + std::to_string(gid_),
                                        "--clear-groups", "--"};
        out.insert(out.end(), argv.begin(), argv.end());
        return out;
    }

    Process::Options options_with_log(const std::string& name) const {
        Process::Options o;
        o.log = root_.path / name;
        // dbus-run-session makes the session bus.
        o.env = {"PATH=/usr/bin:/bin", "HOME=" + home_.string(), "XDG_RUNTIME_DIR=" + run_.string(), "LANG=C.UTF-8",
                 "DBUS_SYSTEM_BUS_ADDRESS=unix:path=" + (run_ / "system_bus").string()};
        return o;
    }

    void install_extension() {
        umf::provider::install_gnome_extension(home_ / ".local/share/gnome-shell/extensions",
                                               umf::provider::GnomeExtensionForm::legacy);
    }

    void chown_all(const fs::path& path) const {
        auto give = [&](const fs::path& p, int result) {
            if (result != 0)
                throw std::runtime_error("cannot give " + p.string() + " to the test user: " + std::strerror(errno));
        };
        give(path, ::chown(path.c_str(), uid_, gid_));
        for (const auto& entry : fs::recursive_directory_iterator(path))
            give(entry.path(), ::lchown(entry.path().c_str(), uid_, gid_));
    }

    void wait_for_path(const fs::path& path, Clock::duration timeout, const std::string& what) const {
        if (!wait_until([&] { return fs::exists(path); }, timeout))
            throw std::runtime_error(what + " did not come up: " + log());
        if (path.filename() == "bus-address")
            wait_until([&] { return !read_file(path).empty(); }, 2s);
    }

    std::string system_bus_config() const {
        return "<!DOCTYPE busconfig PUBLIC \"-//freedesktop//DTD D-Bus Bus Configuration 1.0//EN\"\n"
               " \"http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd\">\n<busconfig><type>system</type>"
               "<listen>unix:path=" + (run_ / "system_bus").string() + "</listen><auth>EXTERNAL</auth>"
               "<policy context=\"default\"><allow user=\"*\"/><allow own=\"*\"/><allow send_destination=\"*\"/>"
               "<allow receive_sender=\"*\"/></policy></busconfig>\n";
    }
    // The usual session bus, which root may also join: the test's foreign
    // caller.
    static std::string session_bus_config() {
        return "<!DOCTYPE busconfig PUBLIC \"-//freedesktop//DTD D-Bus Bus Configuration 1.0//EN\"\n"
               " \"http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd\">\n<busconfig>"
               "<include>/usr/share/dbus-1/session.conf</include>"
               "<policy context=\"default\"><allow user=\"root\"/></policy></busconfig>\n";
    }

    TempDir root_;
    fs::path run_, home_;
    uid_t uid_ = 0;
    gid_t gid_ = 0;
    std::string bus_address_;
    std::unique_ptr<Process> system_bus_;
    std::unique_ptr<Process> shell_;
};

}  // namespace umf::test
