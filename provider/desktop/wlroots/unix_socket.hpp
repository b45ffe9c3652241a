// One request and its answer over a Unix socket, every step under a
// deadline: a compositor that hangs or went away gives a DesktopError, never
// a blocked server thread. Sway's IPC and Hyprland's socket both use it.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace umf::provider {

class UnixSocket {
public:
    // Throws DesktopError when nothing listens at `path`.
    UnixSocket(const std::string& path, std::chrono::steady_clock::time_point deadline);
    ~UnixSocket();
    UnixSocket(const UnixSocket&) = delete;
    UnixSocket& operator=(const UnixSocket&) = delete;

    void write_all(const std::string& bytes);
    // Exactly `count` bytes; throws DesktopError at the deadline or EOF.
    std::string read_exact(std::size_t count);
    // Everything until the peer closes; throws DesktopError at the deadline.
    std::string read_to_end();

private:
    // Waits for `events` on the socket until the deadline; throws at it.
    void wait_for(short events);

    int fd_ = -1;
    std::string path_;
    std::chrono::steady_clock::time_point deadline_;
};

}  // namespace umf::provider
