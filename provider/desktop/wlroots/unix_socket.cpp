#include "provider/desktop/wlroots/unix_socket.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

UnixSocket::UnixSocket(const std::string& path, std::chrono::steady_clock::time_point deadline)
    : path_(path), deadline_(deadline) {
    sockaddr_un address{};
    if (path.empty() || path.size() >= sizeof address.sun_path)
        throw DesktopError("no usable socket path: '" + path + "'");
    fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (fd_ < 0) throw DesktopError(std::string("cannot make a socket: ") + std::strerror(errno));
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, path.c_str(), path.size());
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        if (errno != EINPROGRESS && errno != EAGAIN) {
            const std::string why = std::strerror(errno);
            ::close(fd_);
            fd_ = -1;
            throw DesktopError("nothing answers at " + path + ": " + why);
        }
        wait_for(POLLOUT);
    }
}

UnixSocket::~UnixSocket() {
    if (fd_ >= 0) ::close(fd_);
}

void UnixSocket::wait_for(short events) {
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - std::chrono::steady_clock::now());
        if (left.count() <= 0) throw DesktopError("no answer in time from " + path_);
        pollfd p{fd_, events, 0};
        const int n = ::poll(&p, 1, static_cast<int>(left.count()));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw DesktopError(std::string("poll failed: ") + std::strerror(errno));
        if (n > 0) {
            if ((p.revents & (POLLERR | POLLNVAL)) != 0) throw DesktopError("the connection to " + path_ + " failed");
            return;
        }
    }
}

void UnixSocket::write_all(const std::string& bytes) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
        const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
        } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
            wait_for(POLLOUT);
        } else {
            throw DesktopError("cannot write to " + path_ + ": " + std::strerror(errno));
        }
    }
}

std::string UnixSocket::read_exact(std::size_t count) {
    std::string out;
    out.resize(count);
    std::size_t got = 0;
    while (got < count) {
        const ssize_t n = ::recv(fd_, out.data() + got, count - got, 0);
        if (n > 0) {
            got += static_cast<std::size_t>(n);
        } else if (n == 0) {
            throw DesktopError(path_ + " closed the connection mid-answer");
        } else if (errno == EAGAIN || errno == EINTR) {
            wait_for(POLLIN);
        } else {
            throw DesktopError("cannot read from " + path_ + ": " + std::strerror(errno));
        }
    }
    return out;
}

std::string UnixSocket::read_to_end() {
    std::string out;
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
        if (n > 0) {
            out.append(buffer, static_cast<std::size_t>(n));
        } else if (n == 0) {
            return out;
        } else if (errno == EAGAIN || errno == EINTR) {
            wait_for(POLLIN);
        } else {
            throw DesktopError("cannot read from " + path_ + ": " + std::strerror(errno));
        }
    }
}

}  // namespace umf::provider
