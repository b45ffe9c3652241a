// Running the project's programs from tests: a command to completion with
// its output, or a long-running child (a provider) whose output is read line
// by line and which is stopped with SIGTERM when the test ends.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace umf::test {

struct CommandResult {
    int exit_code = -1;
    std::string out;  // stdout; stderr goes to the test's own
};

inline CommandResult run_command(const std::string& command) {
    CommandResult r;
    FILE* p = ::popen(command.c_str(), "r");
    if (!p) throw std::runtime_error("cannot run " + command);
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, p)) > 0) r.out.append(buffer, n);
    const int status = ::pclose(p);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// `s` as one word of a shell command: in single quotes (the tests' paths
// hold none).
inline std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

// A child process started with execv (no shell); its stdout is a pipe.
class ChildProcess {
public:
    explicit ChildProcess(std::vector<std::string> argv) {
        int pipe_fds[2];
        if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
        pid_ = ::fork();
        if (pid_ < 0) throw std::runtime_error("fork failed");
        if (pid_ == 0) {
            ::dup2(pipe_fds[1], 1);
            std::vector<char*> args;
            for (auto& a : argv) args.push_back(a.data());
            args.push_back(nullptr);
            ::execv(args[0], args.data());
            ::_exit(127);
        }
        ::close(pipe_fds[1]);
        out_fd_ = pipe_fds[0];
    }
    ~ChildProcess() {
        stop();
        if (out_fd_ >= 0) ::close(out_fd_);
    }
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    // Lines of stdout until one satisfies `wanted` (returned) or the timeout
    // passes or the output ends (nullopt). Everything read is kept in output().
    std::optional<std::string> read_until(const std::function<bool(const std::string&)>& wanted,
                                          std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            const auto nl = pending_.find('\n');
            if (nl != std::string::npos) {
                std::string line = pending_.substr(0, nl);
                pending_.erase(0, nl + 1);
                output_ += line + "\n";
                if (wanted(line)) return line;
                continue;
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) return std::nullopt;
            pollfd p{out_fd_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return std::nullopt;
            char buffer[4096];
            const ssize_t n = ::read(out_fd_, buffer, sizeof buffer);
            if (n <= 0) return std::nullopt;
            pending_.append(buffer, static_cast<std::size_t>(n));
        }
    }
    const std::string& output() const { return output_; }
    pid_t pid() const { return pid_; }

    // Reads stdout to its end and waits for the child to exit on its own:
    // its exit code, or -1 when a signal ended it or it outlasted `timeout`
    // (then it is killed).
    int wait(std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
        read_until([](const std::string&) { return false; }, timeout);
        if (!pending_.empty()) output_ += pending_;
        pending_.clear();
        if (pid_ <= 0) return exit_code_;
        return reap(std::chrono::seconds(5));
    }

    // SIGTERM, then the exit code (or -1 when it had to be killed).
    int stop(std::chrono::milliseconds grace = std::chrono::seconds(10)) {
        if (pid_ <= 0) return exit_code_;
        ::kill(pid_, SIGTERM);
        return reap(grace);
    }

private:
    // Waits up to `grace` for the exit, then kills: the exit code, or -1.
    int reap(std::chrono::milliseconds grace) {
        const auto deadline = std::chrono::steady_clock::now() + grace;
        int status = 0;
        while (::waitpid(pid_, &status, WNOHANG) == 0) {
            if (std::chrono::steady_clock::now() > deadline) {
                ::kill(pid_, SIGKILL);
                ::waitpid(pid_, &status, 0);
                pid_ = 0;
                return exit_code_ = -1;
            }
            ::usleep(10000);
        }
        pid_ = 0;
        return exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }

    pid_t pid_ = 0;
    int out_fd_ = -1;
    int exit_code_ = -1;
    std::string pending_;
    std::string output_;
};

}  // namespace umf::test
