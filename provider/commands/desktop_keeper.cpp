#include "provider/commands/desktop_keeper.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

#include "provider/commands/common_options.hpp"

namespace umf::provider {
namespace {

using Clock = std::chrono::steady_clock;

// Up to `timeout` for SIGINT, SIGTERM or SIGCHLD (all blocked in the
// keeper); the signal, or 0 when none came.
int wait_for_signal(std::chrono::milliseconds timeout) {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGCHLD);
    const auto ms = std::max<long long>(timeout.count(), 1);
    const timespec ts{static_cast<time_t>(ms / 1000), static_cast<long>(ms % 1000) * 1'000'000L};
    const int signal = ::sigtimedwait(&set, nullptr, &ts);
    return signal < 0 ? 0 : signal;
}

std::optional<int> reap(pid_t pid, bool block) {
    int status = 0;
    pid_t r;
    do {
        r = ::waitpid(pid, &status, block ? 0 : WNOHANG);
    } while (r < 0 && errno == EINTR);
    if (r == pid) return status;
    return std::nullopt;
}

// SIGTERM (or the signal the keeper got) first, SIGKILL after the grace.
int stop_child(pid_t pid, int signal, std::chrono::seconds grace) {
    ::kill(pid, signal);
    const auto deadline = Clock::now() + grace;
    while (Clock::now() < deadline) {
        if (auto status = reap(pid, false)) return *status;
        wait_for_signal(std::chrono::milliseconds(100));
    }
    ::kill(pid, SIGKILL);
    return reap(pid, true).value_or(0);
}

// The first port a child reports ("8765\n").
void read_port(int fd, std::optional<unsigned short>& port) {
    char text[64];
    const ssize_t n = ::read(fd, text, sizeof text - 1);
    if (n <= 0 || port) return;
    text[n] = 0;
    const long value = std::strtol(text, nullptr, 10);
    if (value > 0 && value <= 65535) port = static_cast<unsigned short>(value);
}

int exit_code_of(int status) {
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return kServeError;
}

}  // namespace

ChildEnd describe_child_end(int wait_status) {
    if (WIFEXITED(wait_status)) {
        const int code = WEXITSTATUS(wait_status);
        const bool own = code == kOk || code == kUsage || code == kConfigError || code == kServeError;
        return {own, "exit " + std::to_string(code)};
    }
    if (WIFSIGNALED(wait_status)) {
        const int signal = WTERMSIG(wait_status);
        const char* name = ::sigabbrev_np(signal);
        return {false, "killed by SIG" + std::string(name ? name : std::to_string(signal).c_str())};
    }
    return {false, "ended"};
}

void tell_keeper_port(const KeeperRole& role, unsigned short port) {
    if (role.port_report_fd < 0) return;
    const std::string text = std::to_string(port) + "\n";
    [[maybe_unused]] const auto n = ::write(role.port_report_fd, text.data(), text.size());
}

std::variant<KeeperRole, int> keep_provider(const KeeperSettings& settings, std::ostream& log) {
    int ports[2];
    if (::pipe2(ports, O_CLOEXEC | O_NONBLOCK) != 0) {
        log << "umf-provider: cannot start the provider: " << std::strerror(errno) << "\n";
        return kServeError;
    }
    sigset_t child_signal;
    sigemptyset(&child_signal);
    sigaddset(&child_signal, SIGCHLD);
    pthread_sigmask(SIG_BLOCK, &child_signal, nullptr);
    const auto done = [&](int code) {
        ::close(ports[0]);
        ::close(ports[1]);
        std::error_code ec;
        std::filesystem::remove(settings.shares_file, ec);
        return code;
    };

    KeeperRole role;
    role.shares_file = settings.shares_file;
    role.port_report_fd = ports[1];
    std::chrono::seconds wait{0};
    Clock::time_point desktop_not_before = Clock::now();
    while (true) {
        log << std::flush;
        const pid_t keeper = ::getpid();
        const pid_t pid = ::fork();
        if (pid < 0) {
            log << "umf-provider: cannot start the provider: " << std::strerror(errno) << "\n";
            return done(kServeError);
        }
        if (pid == 0) {
            // A keeper that is killed takes its child along: the port must
            // not stay taken by a provider no one keeps.
            ::prctl(PR_SET_PDEATHSIG, SIGTERM);
            if (::getppid() != keeper) ::_exit(kServeError);
            ::close(ports[0]);
            pthread_sigmask(SIG_UNBLOCK, &child_signal, nullptr);
            return role;
        }
        const auto started = Clock::now();
        std::optional<int> ended;
        bool display_back = false;
        while (!ended && !display_back) {
            const int signal = wait_for_signal(settings.poll);
            read_port(ports[0], role.port);
            if (signal == SIGINT || signal == SIGTERM) return done(exit_code_of(stop_child(pid, signal, settings.stop_grace)));
            ended = reap(pid, false);
            if (!ended && !role.with_desktop && Clock::now() >= desktop_not_before && settings.display_answers &&
                settings.display_answers()) {
                log << "umf-provider: the display answers again; the provider on the desktop starts again\n";
                const ChildEnd end = describe_child_end(stop_child(pid, SIGTERM, settings.stop_grace));
                if (end.how != "exit 0") log << "umf-provider: the provider without a desktop ended with " << end.how << "\n";
                display_back = true;
            }
        }
        if (display_back) {
            role.with_desktop = true;
            continue;
        }
        const ChildEnd end = describe_child_end(*ended);
        if (end.done) return done(exit_code_of(*ended));
        if (!role.with_desktop) {
            log << "umf-provider: the provider without a desktop ended (" << end.how << ")\n";
            return done(kServeError);
        }
        // The desktop went away under the provider, or the provider failed
        // on it: one that fails soon after each start is tried less often.
        wait = Clock::now() - started < settings.short_life
                   ? std::min<std::chrono::seconds>(std::max<std::chrono::seconds>(wait * 2, std::chrono::seconds(2)),
                                                    settings.longest_wait)
                   : std::chrono::seconds(0);
        desktop_not_before = Clock::now() + wait;
        log << "umf-provider: the provider on the desktop ended (" << end.how
            << "): the display went away, or the provider failed on it. Serving on without a desktop "
               "(boards, shares, puts); the field comes back when the display answers again";
        if (wait.count() > 0) log << " (not before " << wait.count() << " s)";
        log << "\n";
        role.with_desktop = false;
    }
}

}  // namespace umf::provider
