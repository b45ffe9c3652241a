// What a requester is told about a file before it downloads it: its media
// type, size and SHA-256. Hashes are cached by path, size and modification
// time, so repeated grabs of a large file on a board hash it once. A grab is
// answered on one of the server's few threads, so a file too large to hash
// at once (kHashAtOnceBytes) goes out without a hash the first time (the
// protocol makes it optional; the size is still checked) while a background
// thread hashes it for the grabs after.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <set>
#include <thread>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace umf::provider {

// "application/pdf" for "x.PDF"; application/octet-stream when unknown.
std::string mime_for(const std::filesystem::path& file);

// Lowercase hex SHA-256 of a byte string.
std::string sha256_hex(const std::string& bytes);

struct FileFacts {
    std::int64_t size = 0;
    std::string sha256;
};

// 256 MiB hash in about half a second on one core here.
inline constexpr std::int64_t kHashAtOnceBytes = std::int64_t{64} << 20;

class FileFactsCache {
public:
    FileFactsCache();
    ~FileFactsCache();
    FileFactsCache(const FileFactsCache&) = delete;
    FileFactsCache& operator=(const FileFactsCache&) = delete;

    // Size and SHA-256; the hash empty when the file is larger than
    // kHashAtOnceBytes and not hashed yet (it is then queued). Grabs of the
    // same file at the same time hash it once. Throws std::runtime_error
    // naming the file when it is not a readable regular file.
    FileFacts facts(const std::filesystem::path& file);
    // Queues files to be hashed in the background (a board's, at start-up).
    void prepare(const std::vector<std::filesystem::path>& files);

private:
    struct Key {
        std::string path;
        std::int64_t size;
        std::int64_t mtime_ns;
        auto operator<=>(const Key&) const = default;
    };
    void hash_in_background();

    std::mutex mutex_;
    std::condition_variable changed_;
    std::map<Key, std::string> hashes_;
    std::set<std::string> hashing_;         // paths being hashed now, by a grab or the background
    std::deque<std::filesystem::path> queue_;  // for the background thread
    bool stopping_ = false;
    std::thread worker_;
};

}  // namespace umf::provider
