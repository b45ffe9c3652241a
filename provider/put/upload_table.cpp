#include "put/upload_table.hpp"

#include <openssl/rand.h>

#include <algorithm>
#include <stdexcept>

#include "server/pairing.hpp"

namespace umf::provider {

UploadTable::UploadTable(std::chrono::milliseconds ttl, std::size_t max_entries)
    : ttl_(ttl), max_entries_(std::max<std::size_t>(max_entries, 1)) {}

std::string UploadTable::add(UploadEntry entry, Clock::time_point now) {
    unsigned char random[16];
    if (RAND_bytes(random, sizeof random) != 1) throw std::runtime_error("the random generator failed");
    std::string key = base64url(random, sizeof random);
    std::lock_guard lock(mutex_);
    for (auto it = slots_.begin(); it != slots_.end();) it = it->second.expires <= now ? slots_.erase(it) : std::next(it);
    while (slots_.size() >= max_entries_) {
        auto oldest = slots_.begin();
        for (auto it = slots_.begin(); it != slots_.end(); ++it)
            if (it->second.expires < oldest->second.expires) oldest = it;
        slots_.erase(oldest);
    }
    slots_.emplace(key, Slot{std::move(entry), now + ttl_});
    return kUploadPrefix + key;
}

std::optional<UploadEntry> UploadTable::take(std::string_view target, Clock::time_point now) {
    target = target.substr(0, target.find('?'));
    const std::string_view prefix = kUploadPrefix;
    if (target.substr(0, prefix.size()) != prefix) return std::nullopt;
    const std::string_view key = target.substr(prefix.size());
    std::lock_guard lock(mutex_);
    auto it = slots_.find(key);
    if (it == slots_.end()) return std::nullopt;
    Slot slot = std::move(it->second);
    slots_.erase(it);
    if (slot.expires <= now) return std::nullopt;
    return std::move(slot.entry);
}

std::size_t UploadTable::size() const {
    std::lock_guard lock(mutex_);
    return slots_.size();
}

}  // namespace umf::provider
