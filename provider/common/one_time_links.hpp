// Single-use links with a lifetime: "/dl/<key>" for what a grab resolved
// (content/download_table.hpp), "/up/<key>" for what a put may send
// (put/upload_table.hpp). A key is 128 random bits, so links cannot be
// guessed; a request's path is only ever a key into this table, never a path
// on the file system. Thread-safe.
#pragma once

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace umf::provider {

// 22 base64url characters of 128 random bits (OpenSSL's generator). Throws
// std::runtime_error when the generator fails.
std::string random_link_key();

template <class Entry>
class OneTimeLinks {
public:
    using Clock = std::chrono::steady_clock;

    OneTimeLinks(std::string prefix, std::chrono::milliseconds ttl, std::size_t max_entries)
        : prefix_(std::move(prefix)), ttl_(ttl), max_entries_(std::max<std::size_t>(max_entries, 1)) {}

    // The link path (prefix + key). When the table is full the entry that
    // expires first makes room.
    std::string add(Entry entry, Clock::time_point now = Clock::now()) {
        std::string key = random_link_key();
        std::lock_guard lock(mutex_);
        for (auto it = slots_.begin(); it != slots_.end();) it = it->second.expires <= now ? slots_.erase(it) : std::next(it);
        while (slots_.size() >= max_entries_)
            slots_.erase(std::min_element(slots_.begin(), slots_.end(), [](const auto& a, const auto& b) {
                return a.second.expires < b.second.expires;
            }));
        slots_.emplace(key, Slot{std::move(entry), now + ttl_});
        return prefix_ + key;
    }

    // The entry for a request target (prefix + key; a query is ignored),
    // taken out; nullopt when unknown, used or expired.
    std::optional<Entry> take(std::string_view target, Clock::time_point now = Clock::now()) {
        target = target.substr(0, target.find('?'));
        if (target.substr(0, prefix_.size()) != prefix_) return std::nullopt;
        const std::string_view key = target.substr(prefix_.size());
        std::lock_guard lock(mutex_);
        auto it = slots_.find(key);
        if (it == slots_.end()) return std::nullopt;
        Slot slot = std::move(it->second);
        slots_.erase(it);
        if (slot.expires <= now) return std::nullopt;
        return std::move(slot.entry);
    }

    std::size_t size() const {
        std::lock_guard lock(mutex_);
        return slots_.size();
    }
    std::chrono::milliseconds ttl() const { return ttl_; }

private:
    struct Slot {
        Entry entry;
        Clock::time_point expires;
    };

    std::string prefix_;
    std::chrono::milliseconds ttl_;
    std::size_t max_entries_;
    mutable std::mutex mutex_;
    std::map<std::string, Slot, std::less<>> slots_;
};

}  // namespace umf::provider
