// Unix sockets only this user may reach: the control socket and the browser
// link listen in the runtime folder (0700, this user's own), the socket file
// itself 0600, and each connection's peer is checked with SO_PEERCRED.
#pragma once

#include <sys/un.h>

#include <filesystem>
#include <functional>

namespace umf::provider {

// Throws std::runtime_error when the path does not fit a socket address.
sockaddr_un unix_address(const std::filesystem::path& path);

// Binds and listens at `path`. A socket file left by a provider that died is
// replaced; when `answers(path)` says a live one holds it, throws naming it.
// Throws std::runtime_error when the folder is not this user's own or the
// socket cannot listen. Returns the listening descriptor (close-on-exec).
int listen_owner_only(const std::filesystem::path& path,
                      const std::function<bool(const std::filesystem::path&)>& answers);

// A pipe whose write end wakes the socket's thread when it is to stop. On
// failure closes `listen_fd`, removes the socket file at `path` and throws
// std::runtime_error.
void open_wake_pipe(int (&wake)[2], int listen_fd, const std::filesystem::path& path);

// Whether the process at the other end of a connected Unix socket runs as
// this user.
bool peer_is_this_user(int fd);

}  // namespace umf::provider
