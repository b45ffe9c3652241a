// What a requester is told about a file before it downloads it: its media
// type, size and SHA-256. Hashes are cached by path, size and modification
// time, so repeated grabs of a large file on a board hash it once.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

namespace umf::provider {

// "application/pdf" for "x.PDF"; application/octet-stream when unknown.
std::string mime_for(const std::filesystem::path& file);

// Lowercase hex SHA-256 of a byte string.
std::string sha256_hex(const std::string& bytes);

struct FileFacts {
    std::int64_t size = 0;
    std::string sha256;
};

class FileFactsCache {
public:
    // Throws std::runtime_error naming the file when it is not a readable
    // regular file.
    FileFacts facts(const std::filesystem::path& file);

private:
    struct Key {
        std::string path;
        std::int64_t size;
        std::int64_t mtime_ns;
        auto operator<=>(const Key&) const = default;
    };
    std::mutex mutex_;
    std::map<Key, std::string> hashes_;
};

}  // namespace umf::provider
