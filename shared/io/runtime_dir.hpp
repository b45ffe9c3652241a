// Where a running provider keeps the sockets that live as long as it runs:
// $XDG_RUNTIME_DIR/umf, else /tmp/umf-UID, a folder only its user may enter.
// The provider's control socket (`share`, `puts`) and the browser link (the
// browser companion's host) are found there by their port.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace umf {

std::filesystem::path runtime_dir();

// runtime_dir()/provider-PORT.sock: `umf-provider share`, `puts`, `browser status`.
std::filesystem::path control_socket_path(unsigned short port);

// runtime_dir()/browser-PORT.sock: where the browser companion's host connects.
std::filesystem::path browser_socket_path(unsigned short port);

// PORT when `name` is a control socket's file name, "provider-PORT.sock".
std::optional<unsigned short> provider_socket_port(const std::string& name);

// Whether `name` is a browser link's socket file name, "browser-PORT.sock".
bool is_browser_socket_name(const std::string& name);

}  // namespace umf
