#include "provider/content/file_facts.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "native/sha256.hpp"
#include "provider/content/read_lease.hpp"
#include "shared/protocol/media_types.hpp"

namespace umf::provider {

namespace {

std::int64_t nanoseconds(const struct timespec& t) { return std::int64_t{t.tv_sec} * 1000000000 + t.tv_nsec; }

FileIdentity identity_of(const struct stat& st) {
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino),
            static_cast<std::int64_t>(st.st_size), nanoseconds(st.st_mtim)};
}

// A change after a hash stamps the file's ctime with the clock's time
// then, which is coarse (up to 10 ms a tick): a file changed this shortly
// before its hash began could be changed again after it without a new
// ctime, so its hash is not taken as leased.
constexpr std::int64_t kSettledNs = 50'000'000;

// Enough for every file of a large board; beyond it the cache starts over.
constexpr std::size_t kMaxCachedHashes = 1024;

}  // namespace

// The lease is taken before the file's state is read: whatever changed the
// file before is in its ctime, whatever would change it after breaks the lease.
struct FileFactsCache::OpenFile {
    int fd = -1;
    ReadLease lease;
    struct stat st {};
    std::int64_t opened_ns = 0;

    explicit OpenFile(const std::string& what) {
        fd = ::open(what.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) throw std::runtime_error("cannot open " + what + ": " + std::strerror(errno));
        lease = ReadLease(fd);
        std::string why;
        if (::fstat(fd, &st) != 0)
            why = "cannot read " + what + ": " + std::strerror(errno);
        else if (!S_ISREG(st.st_mode))
            why = what + " is not a regular file";
        if (!why.empty()) {
            lease.release();
            ::close(fd);
            throw std::runtime_error(why);
        }
        struct timespec now {};
        ::clock_gettime(CLOCK_REALTIME, &now);
        opened_ns = nanoseconds(now);
    }
    ~OpenFile() {
        lease.release();
        if (fd >= 0) ::close(fd);
    }
    OpenFile(const OpenFile&) = delete;
    OpenFile& operator=(const OpenFile&) = delete;

    // `stop` is looked at between reads: a provider stopping does not wait
    // for the rest of a large file. So is the lease: a program that opens
    // the file for writing meanwhile waits one read, not the whole hash,
    // and the hash is not taken as leased.
    Hashed hash(const std::string& what, const std::atomic<bool>* stop = nullptr) {
        native::Sha256 hash;
        std::vector<char> buffer(1 << 20);
        for (;;) {
            if (stop && stop->load()) throw std::runtime_error("stopped while hashing " + what);
            const ssize_t n = ::read(fd, buffer.data(), buffer.size());
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) throw std::runtime_error("cannot read " + what + ": " + std::strerror(errno));
            if (n == 0) break;
            if (lease.held() && !lease.unbroken()) lease.release();
            hash.update(buffer.data(), static_cast<std::size_t>(n));
        }
        const std::int64_t ctime = nanoseconds(st.st_ctim);
        const bool leased = lease.unbroken() && ctime != 0 && ctime <= opened_ns - kSettledNs;
        return {hash.hex(), leased ? ctime : 0};
    }
};

FileFacts FileFactsCache::facts_of(const Key& key, const Hashed& hashed) {
    return {key.identity.size, hashed.sha256, key.identity, hashed.leased_ctime_ns};
}

std::string mime_for(const std::filesystem::path& file) { return protocol::media_type_for(file.filename().string()); }

std::string sha256_hex(const std::string& bytes) {
    native::Sha256 hash;
    hash.update(bytes.data(), bytes.size());
    return hash.hex();
}

FileFactsCache::FileFactsCache() : worker_([this] { hash_in_background(); }) {}

FileFactsCache::~FileFactsCache() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        queue_.clear();
        waiting_.clear();
    }
    stop_hashing_ = true;
    changed_.notify_all();
    worker_.join();
}

std::optional<FileFacts> FileFactsCache::cached_or_claim(std::unique_lock<std::mutex>& lock, const Key& key) {
    for (;;) {
        if (auto it = hashes_.find(key); it != hashes_.end()) return facts_of(key, it->second);
        if (!hashing_.count(key.path)) break;
        // Someone hashes it now: wait for that rather than read it twice.
        changed_.wait(lock);
    }
    hashing_.insert(key.path);
    return std::nullopt;
}

FileFacts FileFactsCache::hash_claimed(OpenFile& file, const Key& key) {
    Hashed hash;
    try {
        hash = file.hash(key.path);
    } catch (...) {
        std::lock_guard lock(mutex_);
        hashing_.erase(key.path);
        changed_.notify_all();
        throw;
    }
    std::lock_guard lock(mutex_);
    hashing_.erase(key.path);
    if (hashes_.size() > kMaxCachedHashes) hashes_.clear();
    hashes_[key] = hash;
    changed_.notify_all();
    return facts_of(key, hash);
}

FileFacts FileFactsCache::facts(const std::filesystem::path& file) {
    OpenFile f(file.string());
    const Key key{file.string(), identity_of(f.st)};
    std::unique_lock lock(mutex_);
    if (auto known = cached_or_claim(lock, key)) return *known;
    lock.unlock();
    return hash_claimed(f, key);
}

std::optional<FileFacts> FileFactsCache::facts_or_later(const std::filesystem::path& file, Later later) {
    OpenFile f(file.string());
    const Key key{file.string(), identity_of(f.st)};
    std::unique_lock lock(mutex_);
    if (auto it = hashes_.find(key); it != hashes_.end()) return facts_of(key, it->second);
    if (key.identity.size > kHashAtOnceBytes) {
        waiting_[key.path].push_back(std::move(later));
        queue(file);
        return std::nullopt;
    }
    if (auto known = cached_or_claim(lock, key)) return known;
    lock.unlock();
    return hash_claimed(f, key);
}

void FileFactsCache::queue(const std::filesystem::path& file) {
    if (std::find(queue_.begin(), queue_.end(), file) != queue_.end()) return;
    queue_.push_back(file);
    changed_.notify_all();
}

void FileFactsCache::prepare(const std::vector<std::filesystem::path>& files) {
    std::lock_guard lock(mutex_);
    for (const auto& f : files) queue(f);
}

void FileFactsCache::forget(const std::filesystem::path& file) {
    std::lock_guard lock(mutex_);
    const std::string what = file.string();
    std::erase_if(hashes_, [&](const auto& entry) { return entry.first.path == what; });
}

void FileFactsCache::hash_in_background() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        const std::filesystem::path file = queue_.front();
        queue_.pop_front();
        hash_one_in_background(lock, file);
    }
}

void FileFactsCache::hash_one_in_background(std::unique_lock<std::mutex>& lock, const std::filesystem::path& file) {
    const std::string what = file.string();
    // A grab hashing it now: its hash is what the waiting grabs get.
    changed_.wait(lock, [&] { return stopping_ || !hashing_.count(what); });
    if (stopping_) return;
    hashing_.insert(what);
    lock.unlock();
    std::variant<FileFacts, std::string> result;
    bool fresh = false;
    Key key;
    Hashed hashed;
    try {
        OpenFile f(what);
        key = Key{what, identity_of(f.st)};
        std::optional<Hashed> known;
        {
            std::lock_guard guard(mutex_);
            if (auto it = hashes_.find(key); it != hashes_.end()) known = it->second;
        }
        fresh = !known;
        hashed = known ? *known : f.hash(what, &stop_hashing_);
        result = facts_of(key, hashed);
    } catch (const std::exception& e) {
        result = std::string(e.what());
        fresh = false;
    }
    lock.lock();
    hashing_.erase(what);
    if (fresh) {
        if (hashes_.size() > kMaxCachedHashes) hashes_.clear();
        hashes_[key] = hashed;
    }
    std::vector<Later> waiters;
    if (auto it = waiting_.find(what); it != waiting_.end()) {
        waiters = std::move(it->second);
        waiting_.erase(it);
    }
    changed_.notify_all();
    if (stopping_ || waiters.empty()) return;
    lock.unlock();
    for (auto& waiter : waiters) {
        try {
            waiter(result);
        } catch (...) {
            // A waiter's failure is its own (the session it would answer is gone).
        }
    }
    lock.lock();
}

}  // namespace umf::provider
