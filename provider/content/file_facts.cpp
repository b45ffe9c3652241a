#include "content/file_facts.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "native/sha256.hpp"
#include "protocol/media_types.hpp"

namespace umf::provider {

namespace {

std::string hash_fd(int fd, const std::string& what) {
    native::Sha256 hash;
    std::vector<char> buffer(1 << 20);
    for (;;) {
        const ssize_t n = ::read(fd, buffer.data(), buffer.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw std::runtime_error("cannot read " + what + ": " + std::strerror(errno));
        if (n == 0) break;
        hash.update(buffer.data(), static_cast<std::size_t>(n));
    }
    return hash.hex();
}

}  // namespace

std::string mime_for(const std::filesystem::path& file) { return protocol::media_type_for(file.filename().string()); }

std::string sha256_hex(const std::string& bytes) {
    native::Sha256 hash;
    hash.update(bytes.data(), bytes.size());
    return hash.hex();
}

namespace {

struct OpenFile {
    int fd = -1;
    struct stat st {};
    ~OpenFile() {
        if (fd >= 0) ::close(fd);
    }
};

void open_regular(const std::string& what, OpenFile& f) {
    f.fd = ::open(what.c_str(), O_RDONLY | O_CLOEXEC);
    if (f.fd < 0) throw std::runtime_error("cannot open " + what + ": " + std::strerror(errno));
    if (::fstat(f.fd, &f.st) != 0) throw std::runtime_error("cannot read " + what + ": " + std::strerror(errno));
    if (!S_ISREG(f.st.st_mode)) throw std::runtime_error(what + " is not a regular file");
}

}  // namespace

FileFactsCache::FileFactsCache() : worker_([this] { hash_in_background(); }) {}

FileFactsCache::~FileFactsCache() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        queue_.clear();
    }
    changed_.notify_all();
    worker_.join();
}

FileFacts FileFactsCache::facts(const std::filesystem::path& file) {
    const std::string what = file.string();
    OpenFile f;
    open_regular(what, f);
    const Key key{what, static_cast<std::int64_t>(f.st.st_size),
                  static_cast<std::int64_t>(f.st.st_mtim.tv_sec) * 1000000000 + f.st.st_mtim.tv_nsec};
    {
        std::unique_lock lock(mutex_);
        for (;;) {
            if (auto it = hashes_.find(key); it != hashes_.end()) return {key.size, it->second};
            if (key.size > kHashAtOnceBytes) {
                if (!hashing_.count(what) && std::find(queue_.begin(), queue_.end(), file) == queue_.end()) {
                    queue_.push_back(file);
                    changed_.notify_all();
                }
                return {key.size, ""};
            }
            if (!hashing_.count(what)) break;
            // Someone hashes it now: wait for that rather than read it twice.
            changed_.wait(lock);
        }
        hashing_.insert(what);
    }
    std::string hash;
    try {
        hash = hash_fd(f.fd, what);
    } catch (...) {
        std::lock_guard lock(mutex_);
        hashing_.erase(what);
        changed_.notify_all();
        throw;
    }
    std::lock_guard lock(mutex_);
    hashing_.erase(what);
    if (hashes_.size() > 1024) hashes_.clear();
    hashes_[key] = hash;
    changed_.notify_all();
    return {key.size, hash};
}

void FileFactsCache::prepare(const std::vector<std::filesystem::path>& files) {
    std::lock_guard lock(mutex_);
    for (const auto& f : files) queue_.push_back(f);
    changed_.notify_all();
}

void FileFactsCache::hash_in_background() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        const std::filesystem::path file = queue_.front();
        queue_.pop_front();
        const std::string what = file.string();
        if (hashing_.count(what)) continue;
        hashing_.insert(what);
        lock.unlock();
        std::optional<std::pair<Key, std::string>> done;
        try {
            OpenFile f;
            open_regular(what, f);
            const Key key{what, static_cast<std::int64_t>(f.st.st_size),
                          static_cast<std::int64_t>(f.st.st_mtim.tv_sec) * 1000000000 + f.st.st_mtim.tv_nsec};
            done.emplace(key, hash_fd(f.fd, what));
        } catch (const std::exception&) {
            // Gone or unreadable: the grab that needs it will say so.
        }
        lock.lock();
        hashing_.erase(what);
        if (done) {
            if (hashes_.size() > 1024) hashes_.clear();
            hashes_[done->first] = done->second;
        }
        changed_.notify_all();
    }
}

}  // namespace umf::provider
