// Programs a test starts and must not outlive it, and an X server of the
// test's own (Xvfb): what the X11 tests and the board window test share.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace umf::test {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

inline std::optional<fs::path> find_program(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "/usr/bin:/bin");
    for (std::string dir; std::getline(dirs, dir, ':');)
        if (!dir.empty() && ::access((fs::path(dir) / name).c_str(), X_OK) == 0) return fs::path(dir) / name;
    return std::nullopt;
}

// The test's environment with some variables replaced.
inline std::vector<std::string> environment_with(const std::map<std::string, std::string>& overrides) {
    std::vector<std::string> env;
    for (char** entry = environ; *entry; ++entry) {
        const std::string text = *entry;
        if (!overrides.count(text.substr(0, text.find('=')))) env.push_back(text);
    }
    for (const auto& [name, value] : overrides) env.push_back(name + "=" + value);
    return env;
}

// A process the test started, stopped with its group (TERM, then KILL) and
// reaped when the guard goes, and killed by the kernel should the test die
// first.
class Process {
public:
    struct Options {
        fs::path cwd = "/";
        std::vector<std::string> env = environment_with({});
        fs::path log;          // stdout and stderr; /dev/null when empty
        int stdout_fd = -1;    // instead of the log for stdout
        int stdin_fd = -1;     // instead of /dev/null for stdin
        int inherited_fd = -1;  // kept open across exec
    };

    Process(const std::vector<std::string>& argv, const Options& options) {
        std::vector<char*> args, env;
        for (const auto& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
        for (const auto& entry : options.env) env.push_back(const_cast<char*>(entry.c_str()));
        args.push_back(nullptr);
        env.push_back(nullptr);
        const std::string log = options.log.empty() ? "/dev/null" : options.log.string();
        pid_ = ::fork();
        if (pid_ < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
        if (pid_ == 0) become(args, env, log, options);
        // A group of its own, so what it starts goes with it.
        ::setpgid(pid_, pid_);
    }
    ~Process() { stop(); }
    Process(const Process&) = delete;
    Process& operator=(const Process&) = delete;

    pid_t pid() const { return pid_; }

    // The exit status, waiting up to `timeout`; nullopt when still running.
    std::optional<int> wait_exit(Clock::duration timeout) {
        const auto deadline = Clock::now() + timeout;
        do {
            int status = 0;
            if (::waitpid(pid_, &status, WNOHANG) == pid_) {
                pid_ = -1;
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            std::this_thread::sleep_for(5ms);
        } while (Clock::now() < deadline);
        return std::nullopt;
    }

    void stop() {
        if (pid_ <= 0) return;
        ::kill(-pid_, SIGTERM);
        const auto deadline = Clock::now() + 2s;
        while (!exited() && Clock::now() < deadline) std::this_thread::sleep_for(5ms);
        // Reaped only after this, so the group's id cannot name another's.
        ::kill(-pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
        pid_ = -1;
    }

private:
    // Without reaping it.
    bool exited() const {
        siginfo_t info{};
        return ::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid_;
    }

    [[noreturn]] static void become(std::vector<char*>& args, std::vector<char*>& env, const std::string& log,
                                    const Options& options) {
        ::setpgid(0, 0);
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        const int null = ::open("/dev/null", O_RDONLY);
        const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0600);
        if (null < 0 || out < 0 || ::chdir(options.cwd.c_str()) != 0) ::_exit(126);
        ::dup2(options.stdin_fd >= 0 ? options.stdin_fd : null, STDIN_FILENO);
        ::dup2(options.stdout_fd >= 0 ? options.stdout_fd : out, STDOUT_FILENO);
        ::dup2(out, STDERR_FILENO);
        if (options.inherited_fd >= 0) ::fcntl(options.inherited_fd, F_SETFD, 0);
        ::execvpe(args[0], args.data(), env.data());
        ::_exit(127);
    }

    pid_t pid_ = -1;
};

// A process started in `dir` with `env`, its output in dir/log.
inline Process::Options logged_in(const fs::path& dir, const std::vector<std::string>& env, const std::string& log) {
    Process::Options o;
    o.cwd = dir;
    o.env = env;
    o.log = dir / log;
    return o;
}

// A file's whole text ("" when it cannot be read).
inline std::string read_text(const fs::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Reads from `fd` until EOF, `stop_at` or the deadline.
inline std::string read_until(int fd, Clock::time_point deadline, char stop_at = '\0') {
    std::string text;
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        pollfd pfd{fd, POLLIN, 0};
        if (left <= 0 || ::poll(&pfd, 1, static_cast<int>(left)) <= 0) return text;
        char buffer[256];
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n <= 0) return text;
        text.append(buffer, static_cast<std::size_t>(n));
        if (stop_at && text.find(stop_at) != std::string::npos) return text;
    }
}

// A command's stdout; throws when it fails or outlasts the timeout.
inline std::string run(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                Clock::duration timeout = 10s) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    Process::Options options;
    options.env = env;
    options.stdout_fd = fds[1];
    Process process(argv, options);
    ::close(fds[1]);
    const std::string out = read_until(fds[0], Clock::now() + timeout);
    ::close(fds[0]);
    const auto status = process.wait_exit(1s);
    std::string command;
    for (const auto& arg : argv) command += arg + " ";
    if (!status) throw std::runtime_error("timed out: " + command);
    if (*status != 0) throw std::runtime_error("failed (" + std::to_string(*status) + "): " + command);
    return out;
}

template <class Predicate>
bool wait_until(Predicate done, Clock::duration timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!done()) {
        if (Clock::now() > deadline) return false;
        std::this_thread::sleep_for(20ms);
    }
    return true;
}

// An Xvfb of the test's own. It picks a free display itself and names it on
// -displayfd once it accepts connections.
struct XServer {
    std::unique_ptr<Process> process;
    std::string display;
};

inline XServer start_xvfb(const fs::path& log, const std::string& screen = "1280x800x24") {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    Process::Options o;
    o.log = log;
    o.inherited_fd = fds[1];
    XServer server;
    server.process = std::make_unique<Process>(
        std::vector<std::string>{"Xvfb", "-displayfd", std::to_string(fds[1]), "-screen", "0", screen,
                                 "-nolisten", "tcp", "-noreset"},
        o);
    ::close(fds[1]);
    const std::string number = read_until(fds[0], Clock::now() + 10s, '\n');
    ::close(fds[0]);
    if (number.empty() || number.back() != '\n') {
        std::ifstream in(log);
        throw std::runtime_error("Xvfb did not start: " + std::string(std::istreambuf_iterator<char>(in), {}));
    }
    server.display = ":" + number.substr(0, number.size() - 1);
    const fs::path socket = "/tmp/.X11-unix/X" + number.substr(0, number.size() - 1);
    if (!wait_until([&] { return fs::exists(socket); }, 5s))
        throw std::runtime_error("Xvfb made no socket " + socket.string());
    return server;
}

// openbox on the display `options.env` names, once it has taken over: it
// runs its --startup command only after it manages the windows already
// there and watches for new ones. (Its _NET_SUPPORTING_WM_CHECK comes
// earlier: a window mapped in between is never managed, so it is neither
// listed nor moved.) `ready` is a path of the test's own the command touches.
inline std::unique_ptr<Process> start_openbox(Process::Options options, const fs::path& ready) {
    fs::remove(ready);
    const fs::path log = options.log;
    auto openbox = std::make_unique<Process>(
        std::vector<std::string>{"openbox", "--sm-disable", "--startup", "touch '" + ready.string() + "'"}, options);
    if (!wait_until([&] { return fs::exists(ready); }, 10s)) {
        std::ifstream in(log);
        throw std::runtime_error("openbox did not start: " + std::string(std::istreambuf_iterator<char>(in), {}));
    }
    return openbox;
}

}  // namespace umf::test
