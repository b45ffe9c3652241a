// The host's way to the running provider: the browser link's socket in the
// user's runtime folder (shared/io/runtime_dir.hpp). Only a socket in a
// folder of this user's own, mode 0700, served by a process of this user, is
// taken: the host talks to nothing else.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace umf::browser {

// The browser link sockets in `dir`, the newest first; none when the folder
// is not this user's own (0700, not a link).
std::vector<std::filesystem::path> provider_sockets(const std::filesystem::path& dir);

// A connected descriptor to the first of `sockets` that a process of this
// user serves, or -1. `why` says what failed when none did.
int connect_to_provider(const std::vector<std::filesystem::path>& sockets, std::string& why);

}  // namespace umf::browser
