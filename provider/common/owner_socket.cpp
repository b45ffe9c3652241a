#include "provider/common/owner_socket.hpp"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace umf::provider {

sockaddr_un unix_address(const std::filesystem::path& path) {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    const std::string s = path.string();
    if (s.size() >= sizeof addr.sun_path) throw std::runtime_error("the socket path is too long: " + s);
    std::memcpy(addr.sun_path, s.c_str(), s.size() + 1);
    return addr;
}

int listen_owner_only(const std::filesystem::path& path,
                      const std::function<bool(const std::filesystem::path&)>& answers) {
    const auto dir = path.parent_path();
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::getuid())
        throw std::runtime_error("the socket folder " + dir.string() + " is not this user's own folder");
    ::chmod(dir.c_str(), 0700);
    const sockaddr_un addr = unix_address(path);
    if (std::filesystem::exists(path, ec)) {
        if (answers && answers(path)) throw std::runtime_error("another provider already answers at " + path.string());
        ::unlink(path.c_str());
    }
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw std::runtime_error(std::string("cannot make a socket: ") + std::strerror(errno));
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 || ::chmod(path.c_str(), 0600) != 0 ||
        ::listen(fd, 8) != 0) {
        const std::string why = std::strerror(errno);
        ::close(fd);
        throw std::runtime_error("cannot listen on " + path.string() + ": " + why);
    }
    return fd;
}

void open_wake_pipe(int (&wake)[2], int listen_fd, const std::filesystem::path& path) {
    if (::pipe2(wake, O_CLOEXEC) == 0) return;
    const std::string why = std::strerror(errno);
    ::close(listen_fd);
    ::unlink(path.c_str());
    throw std::runtime_error("cannot listen on " + path.string() + ": " + why);
}

bool peer_is_this_user(int fd) {
    ucred cred{};
    socklen_t len = sizeof cred;
    return ::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0 && cred.uid == ::getuid();
}

}  // namespace umf::provider
