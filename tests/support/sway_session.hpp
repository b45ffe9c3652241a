// A headless Sway of the test's own, run as an unprivileged user (sway
// refuses root; CI runs as root), with its own XDG_RUNTIME_DIR, Xwayland,
// and clients started as that user. The test itself (root) reaches the
// Wayland and IPC sockets by their paths.
#pragma once

#include <grp.h>
#include <pwd.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::test {

inline constexpr const char* kSwayTestUser = "umf-desktop-test";

class SwaySession {
public:
    // Why sway cannot run here, or nullopt.
    static std::optional<std::string> cannot_run() {
        for (const char* program : {"sway", "swaymsg", "setpriv", "foot", "xterm", "grim", "Xwayland"})
            if (!find_program(program)) return std::string(program) + " is not installed";
        if (::geteuid() != 0 && !::getpwnam(kSwayTestUser)) return std::string("needs root to make the test user");
        return std::nullopt;
    }

    SwaySession() : dir_("umf-sway") {
        ensure_user();
        fs::permissions(dir_.path, fs::perms::owner_all | fs::perms::group_exec | fs::perms::others_exec);
        runtime_dir_ = dir_.path / "run";
        fs::create_directory(runtime_dir_);
        if (::chown(runtime_dir_.c_str(), uid_, gid_) != 0) throw std::runtime_error("cannot chown the runtime dir");
        fs::permissions(runtime_dir_, fs::perms::owner_all);
        const fs::path config = dir_.path / "config";
        std::ofstream(config) << "output HEADLESS-1 resolution 1920x1080 position 0 0\n"
                                 "xwayland enable\n"
                                 "default_border normal\n"
                                 "focus_follows_mouse no\n";
        fs::permissions(config, fs::perms::owner_read | fs::perms::owner_write | fs::perms::others_read);
        Process::Options o;
        o.log = dir_.path / "sway.log";
        o.env = base_env({{"WLR_BACKENDS", "headless"}, {"WLR_LIBINPUT_NO_DEVICES", "1"}, {"WLR_RENDERER", "pixman"}});
        sway_ = std::make_unique<Process>(as_user({"sway", "-c", config.string()}), o);
        if (!wait_until([&] { return !socket_matching("wayland-").empty() && !socket_matching("sway-ipc.").empty(); }, 20s))
            throw std::runtime_error("sway made no sockets: " + log());
        wayland_socket_ = socket_matching("wayland-");
        swaysock_ = socket_matching("sway-ipc.");
        // Xwayland's display, as sway gives it to what it starts.
        swaymsg({"exec", "echo $DISPLAY > " + (runtime_dir_ / "display").string()});
        std::string display;
        wait_until([&] {
            std::ifstream in(runtime_dir_ / "display");
            return std::getline(in, display) && !display.empty();
        }, 10s);
        x_display_ = display;
    }

    const std::string& wayland_socket() const { return wayland_socket_; }  // a path
    const std::string& swaysock() const { return swaysock_; }
    const std::string& x_display() const { return x_display_; }
    std::string runtime_dir() const { return runtime_dir_.string(); }
    const fs::path& dir() const { return dir_.path; }
    Process& sway() { return *sway_; }

    // A client as the test user, on Wayland (and Xwayland when it wants X).
    std::unique_ptr<Process> start_client(const std::vector<std::string>& argv) const {
        Process::Options o;
        o.log = dir_.path / "clients.log";
        o.env = client_env();
        return std::make_unique<Process>(as_user(argv), o);
    }

    std::vector<std::string> client_env() const {
        return base_env({{"WAYLAND_DISPLAY", wayland_socket_}, {"DISPLAY", x_display_}, {"SWAYSOCK", swaysock_}});
    }

    // swaymsg's output; throws when it fails.
    std::string swaymsg(const std::vector<std::string>& args) const {
        std::vector<std::string> argv{"swaymsg", "-s", swaysock_};
        argv.insert(argv.end(), args.begin(), args.end());
        return run(argv, environment_with({}));
    }

    std::string log() const {
        std::ifstream in(dir_.path / "sway.log");
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

private:
    void ensure_user() {
        if (!::getpwnam(kSwayTestUser))
            run({"useradd", "--system", "--create-home", kSwayTestUser}, environment_with({}), 30s);
        const passwd* user = ::getpwnam(kSwayTestUser);
        if (!user) throw std::runtime_error("no test user");
        uid_ = user->pw_uid;
        gid_ = user->pw_gid;
        home_ = user->pw_dir;
    }

    std::vector<std::string> as_user(const std::vector<std::string>& argv) const {
        std::vector<std::string> out{"setpriv", "--reuid=" + std::to_string(uid_), "--regid=" + std::to_string(gid_),
                                     "--clear-groups", "--"};
        out.insert(out.end(), argv.begin(), argv.end());
        return out;
    }

    std::vector<std::string> base_env(std::map<std::string, std::string> extra) const {
        std::map<std::string, std::string> env{{"PATH", "/usr/local/bin:/usr/bin:/bin"},
                                               {"HOME", home_},
                                               {"USER", kSwayTestUser},
                                               {"XDG_RUNTIME_DIR", runtime_dir_.string()}};
        for (auto& [k, v] : extra) env[k] = v;
        std::vector<std::string> out;
        for (const auto& [k, v] : env) out.push_back(k + "=" + v);
        return out;
    }

    std::string socket_matching(const std::string& prefix) const {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(runtime_dir_, ec)) {
            const std::string name = entry.path().filename().string();
            if (name.rfind(prefix, 0) == 0 && entry.is_socket()) return entry.path().string();
        }
        return {};
    }

    TempDir dir_;
    fs::path runtime_dir_;
    uid_t uid_ = 0;
    gid_t gid_ = 0;
    std::string home_;
    std::unique_ptr<Process> sway_;
    std::string wayland_socket_, swaysock_, x_display_;
};

}  // namespace umf::test
