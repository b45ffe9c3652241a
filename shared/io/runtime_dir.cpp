#include "io/runtime_dir.hpp"

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

bool is_browser_socket_name(const std::string& name) {
    const std::string head = "browser-", tail = ".sock";
    if (name.size() <= head.size() + tail.size() || name.size() > head.size() + 5 + tail.size()) return false;
    if (name.compare(0, head.size(), head) != 0 || name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
        return false;
    for (std::size_t i = head.size(); i < name.size() - tail.size(); ++i)
        if (name[i] < '0' || name[i] > '9') return false;
    return true;
}

}  // namespace umf
