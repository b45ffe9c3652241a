// The provider's private runtime folder, $XDG_RUNTIME_DIR/umf: where the
// field's images go for the Shell extension and its snapshots come back. The
// extension reads and writes nowhere else and makes the same checks, so a
// file there is known to be the user's own.
#pragma once

#include <filesystem>

namespace umf::provider {

// The folder, made (0700) when missing. Throws DesktopError when there is no
// XDG_RUNTIME_DIR, or the folder is a symbolic link, not this user's, or
// writable by group or others.
std::filesystem::path private_runtime_folder();

}  // namespace umf::provider
