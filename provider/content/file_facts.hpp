// What a requester is told about a file before it downloads it: its media
// type, size and SHA-256. Every file offered carries its SHA-256, so the
// phone can check what arrives and the download can check what it sends
// (content/verified_file_body.hpp). Hashes are cached by path, device, inode,
// size and modification time, so repeated grabs of a large file on a board
// hash it once. A grab is answered on one of the server's few threads, so a
// file too large to hash at once (kHashAtOnceBytes) is hashed by a
// background thread and its grab answered from there when it is done.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace umf::provider {

// "application/pdf" for "x.PDF"; application/octet-stream when unknown.
std::string mime_for(const std::filesystem::path& file);

// Lowercase hex SHA-256 of a byte string.
std::string sha256_hex(const std::string& bytes);

// Which file, in which state: what a download compares before its first
// byte. A file rewritten in place keeps its inode but not its mtime; one
// replaced by a rename gets another inode.
struct FileIdentity {
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    std::int64_t size = 0;
    std::int64_t mtime_ns = 0;
    auto operator<=>(const FileIdentity&) const = default;
};

struct FileFacts {
    std::int64_t size = 0;
    std::string sha256;
    FileIdentity identity;
    // When the hash was taken under a read lease nobody broke
    // (read_lease.hpp), the file's ctime then; else 0. A download that gets
    // a lease of its own and finds the same ctime sends the file without
    // hashing it again.
    std::int64_t leased_ctime_ns = 0;
};

// 256 MiB hash in about half a second on one core here.
inline constexpr std::int64_t kHashAtOnceBytes = std::int64_t{64} << 20;

class FileFactsCache {
public:
    // The facts once a background hash is done, or why they cannot be had.
    using Later = std::function<void(const std::variant<FileFacts, std::string>&)>;

    FileFactsCache();
    ~FileFactsCache();
    FileFactsCache(const FileFactsCache&) = delete;
    FileFactsCache& operator=(const FileFactsCache&) = delete;

    // Size, SHA-256 and identity, hashing now whatever the size. Grabs of
    // the same file at the same time hash it once. Throws std::runtime_error
    // naming the file when it is not a readable regular file.
    FileFacts facts(const std::filesystem::path& file);
    // The same when known or small enough to hash now; else nullopt, the
    // file is queued, and `later` is called on the hashing thread when it is
    // done (not called when the cache is destroyed first). Throws as facts().
    std::optional<FileFacts> facts_or_later(const std::filesystem::path& file, Later later);
    // Queues files to be hashed in the background (a board's, at start-up).
    void prepare(const std::vector<std::filesystem::path>& files);
    // Drops what is known of a file: its bytes were found not to match its
    // hash (changed without a new mtime), so the next grab hashes it again.
    void forget(const std::filesystem::path& file);

private:
    struct Key {
        std::string path;
        FileIdentity identity;
        auto operator<=>(const Key&) const = default;
    };
    struct Hashed {
        std::string sha256;
        std::int64_t leased_ctime_ns = 0;
    };
    struct OpenFile;
    static FileFacts facts_of(const Key& key, const Hashed& hashed);
    std::optional<FileFacts> cached_or_claim(std::unique_lock<std::mutex>& lock, const Key& key);
    FileFacts hash_claimed(OpenFile& file, const Key& key);
    void queue(const std::filesystem::path& file);
    void hash_in_background();
    void hash_one_in_background(std::unique_lock<std::mutex>& lock, const std::filesystem::path& file);

    std::mutex mutex_;
    std::condition_variable changed_;
    std::map<Key, Hashed> hashes_;
    std::set<std::string> hashing_;         // paths being hashed now, by a grab or the background
    std::deque<std::filesystem::path> queue_;  // for the background thread
    std::map<std::string, std::vector<Later>> waiting_;  // grabs answered when their file is hashed
    bool stopping_ = false;
    std::atomic<bool> stop_hashing_{false};
    std::thread worker_;
};

}  // namespace umf::provider
