#include "browser/host/provider_socket.hpp"

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "shared/io/runtime_dir.hpp"

namespace umf::browser {

namespace fs = std::filesystem;

std::vector<fs::path> provider_sockets(const fs::path& dir) {
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::getuid() || (st.st_mode & 077) != 0)
        return {};
    std::vector<std::pair<fs::file_time_type, fs::path>> found;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        if (!is_browser_socket_name(entry.path().filename().string()) || !entry.is_socket(ec)) continue;
        found.emplace_back(entry.last_write_time(ec), entry.path());
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<fs::path> out;
    for (auto& f : found) out.push_back(std::move(f.second));
    return out;
}

int connect_to_provider(const std::vector<fs::path>& sockets, std::string& why) {
    why = sockets.empty() ? "no provider is running (no browser-PORT.sock in " + runtime_dir().string() + ")" : "";
    for (const fs::path& path : sockets) {
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        const std::string s = path.string();
        if (s.size() >= sizeof addr.sun_path) continue;
        std::memcpy(addr.sun_path, s.c_str(), s.size() + 1);
        const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd < 0) continue;
        ucred cred{};
        socklen_t len = sizeof cred;
        if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0 &&
            ::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0 && cred.uid == ::getuid())
            return fd;
        why = s + ": " + (errno ? std::strerror(errno) : "served by another user");
        ::close(fd);
    }
    return -1;
}

}  // namespace umf::browser
