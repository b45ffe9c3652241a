// A file's size and SHA-256, as the requester announces a put: read once,
// piece by piece, so no file is ever held whole in memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "native/hash_checkpoints.hpp"

namespace umf::requester {

struct FileDigest {
    std::int64_t size = 0;
    std::string sha256;
    // The hash's states along the file: a resumed upload's
    // Upload-Prefix-SHA256 costs at most one step of reading.
    std::shared_ptr<native::HashCheckpoints> checkpoints;
};

// The size and SHA-256 of a regular file, read once. Throws
// std::runtime_error naming the file when it cannot be read or is not a
// regular file.
FileDigest digest_file(const std::filesystem::path& file);

}  // namespace umf::requester
