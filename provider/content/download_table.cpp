#include "provider/content/download_table.hpp"

#include <algorithm>

#include "provider/common/link_key.hpp"

namespace umf::provider {

void DownloadTable::forget_expired(Clock::time_point now) {
    for (auto it = slots_.begin(); it != slots_.end();)
        it = it->second.transfers == 0 && it->second.expires <= now ? slots_.erase(it) : std::next(it);
}

std::string DownloadTable::add(DownloadEntry entry, Clock::time_point now) {
    std::string key = random_link_key();
    std::lock_guard lock(mutex_);
    forget_expired(now);
    while (slots_.size() >= max_entries_) {
        auto first = slots_.end();
        for (auto it = slots_.begin(); it != slots_.end(); ++it)
            if (it->second.transfers == 0 && (first == slots_.end() || it->second.expires < first->second.expires))
                first = it;
        if (first == slots_.end()) break;  // every one is being sent: room is made when they end
        slots_.erase(first);
    }
    slots_.emplace(key, Slot{std::make_shared<const DownloadEntry>(std::move(entry)),
                             std::make_shared<native::HashCheckpoints>(), now + ttl_, 0});
    return kDownloadPrefix + key;
}

std::optional<DownloadCheckout> DownloadTable::begin(std::string_view target, Clock::time_point now) {
    target = target.substr(0, target.find('?'));
    const std::string_view prefix = kDownloadPrefix;
    if (target.substr(0, prefix.size()) != prefix) return std::nullopt;
    const std::string_view key = target.substr(prefix.size());
    std::lock_guard lock(mutex_);
    auto it = slots_.find(key);
    if (it == slots_.end()) return std::nullopt;
    if (it->second.transfers == 0 && it->second.expires <= now) {
        slots_.erase(it);
        return std::nullopt;
    }
    ++it->second.transfers;
    return DownloadCheckout{std::string(key), it->second.entry, it->second.checkpoints};
}

void DownloadTable::end(const DownloadCheckout& checkout, bool complete, Clock::time_point now) {
    std::lock_guard lock(mutex_);
    auto it = slots_.find(checkout.key);
    if (it == slots_.end()) return;
    it->second.transfers = std::max(0, it->second.transfers - 1);
    if (complete) {
        slots_.erase(it);
        return;
    }
    it->second.expires = now + ttl_;
}

std::size_t DownloadTable::size() const {
    std::lock_guard lock(mutex_);
    return slots_.size();
}

}  // namespace umf::provider
