// A received file put in place under a name nobody uses yet: the requester's
// grabs and the provider's puts both write into a private temporary file in
// the target folder and store it here, so a file the user already has is
// never replaced, even by one appearing at the same moment.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace umf::io {

// Moves `temp` (in `dir`) to dir / numbered_name(name, n) for the first n
// whose name is free, and returns that name. The move fails on an existing
// target atomically (renameat2 RENAME_NOREPLACE, or a hard link where the
// file system lacks it). Throws std::runtime_error naming the file.
std::string store_under_free_name(const std::filesystem::path& temp, const std::filesystem::path& dir,
                                  const std::string& name);

}  // namespace umf::io
