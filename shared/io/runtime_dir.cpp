#include "shared/io/runtime_dir.hpp"

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace umf {

std::filesystem::path runtime_dir() {
    const char* runtime = std::getenv("XDG_RUNTIME_DIR");
    return runtime && *runtime ? std::filesystem::path(runtime) / "umf"
                               : std::filesystem::path("/tmp") / ("umf-" + std::to_string(::getuid()));
}

std::filesystem::path control_socket_path(unsigned short port) {
    return runtime_dir() / ("provider-" + std::to_string(port) + ".sock");
}

std::filesystem::path browser_socket_path(unsigned short port) {
    return runtime_dir() / ("browser-" + std::to_string(port) + ".sock");
}

namespace {

// PORT of "HEAD-PORT.sock" (1 to 5 digits, at most 65535).
std::optional<unsigned short> socket_port(const std::string& name, const std::string& head) {
    const std::string tail = ".sock";
    if (name.size() <= head.size() + tail.size() || name.size() > head.size() + 5 + tail.size()) return std::nullopt;
    if (name.compare(0, head.size(), head) != 0 || name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
        return std::nullopt;
    unsigned long port = 0;
    for (std::size_t i = head.size(); i < name.size() - tail.size(); ++i) {
        if (name[i] < '0' || name[i] > '9') return std::nullopt;
        port = port * 10 + static_cast<unsigned long>(name[i] - '0');
    }
    if (port > 65535) return std::nullopt;
    return static_cast<unsigned short>(port);
}

}  // namespace

std::optional<unsigned short> provider_socket_port(const std::string& name) { return socket_port(name, "provider-"); }

bool is_browser_socket_name(const std::string& name) { return socket_port(name, "browser-").has_value(); }

}  // namespace umf
