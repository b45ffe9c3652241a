// Files only their owner may read (keys, pairing tokens), written so that
// readers see the old contents or the new, never half, and never readable by
// others on the way: a temporary file created 0600 beside the target, fsync,
// then a rename.
#pragma once

#include <filesystem>
#include <string>

namespace umf {

// Throws umf::FileWriteError (io/atomic_file.hpp) naming the path and why;
// the target is untouched then.
void write_private_file(const std::filesystem::path& path, const std::string& bytes);

}  // namespace umf
