#include "provider/desktop/display_socket.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>

namespace umf::provider {
namespace {

// ":0", ":0.1", "unix:0" -> "0"; "host:0" or anything else -> "".
std::string local_x_display_number(const std::string& display) {
    std::string rest;
    if (display.rfind("unix:", 0) == 0) rest = display.substr(5);
    else if (!display.empty() && display[0] == ':') rest = display.substr(1);
    else return {};
    rest = rest.substr(0, rest.find('.'));
    if (rest.empty() || rest.find_first_not_of("0123456789") != std::string::npos) return {};
    return rest;
}

bool socket_accepts(const DisplaySocket& socket) {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string path = socket.path.string();
    const std::size_t offset = socket.abstract ? 1 : 0;  // abstract: a leading NUL
    if (path.size() + offset >= sizeof(address.sun_path)) return false;
    std::memcpy(address.sun_path + offset, path.data(), path.size());
    const socklen_t length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + offset + path.size() +
                                                    (socket.abstract ? 0 : 1));
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return false;
    const bool ok = ::connect(fd, reinterpret_cast<const sockaddr*>(&address), length) == 0;
    ::close(fd);
    return ok;
}

}  // namespace

std::vector<DisplaySocket> display_sockets(const DesktopFacts& facts, const std::string& runtime_dir) {
    std::vector<DisplaySocket> out;
    if (!facts.wayland_display.empty()) {
        const std::filesystem::path name(facts.wayland_display);
        out.push_back({"Wayland display " + facts.wayland_display,
                       name.is_absolute() || runtime_dir.empty() ? name : std::filesystem::path(runtime_dir) / name});
    }
    const std::string number = local_x_display_number(facts.x_display);
    if (!number.empty()) {
        const std::string path = "/tmp/.X11-unix/X" + number;
        out.push_back({"X display " + facts.x_display, path, false});
        out.push_back({"X display " + facts.x_display, path, true});
    }
    return out;
}

bool displays_answer(const DesktopFacts& facts, const std::string& runtime_dir) {
    const auto sockets = display_sockets(facts, runtime_dir);
    // Each display counts once: an X server answers on its file or its abstract name.
    for (std::size_t i = 0; i < sockets.size();) {
        std::size_t end = i;
        bool answered = false;
        for (; end < sockets.size() && sockets[end].what == sockets[i].what; ++end)
            answered = answered || socket_accepts(sockets[end]);
        if (!answered) return false;
        i = end;
    }
    return true;
}

}  // namespace umf::provider
