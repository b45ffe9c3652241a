#include "provider/put/upload_table.hpp"

#include "provider/common/link_key.hpp"

namespace umf::provider {

std::string UploadTable::add(UploadEntry entry, Clock::time_point now) {
    std::string key = random_link_key();
    std::lock_guard lock(mutex_);
    // Links nobody used go quietly; broken uploads wait for take_abandoned,
    // which tells their sessions.
    for (auto it = slots_.begin(); it != slots_.end();)
        it = !it->second.sink && it->second.requests == 0 && it->second.expires <= now ? slots_.erase(it) : std::next(it);
    while (slots_.size() >= max_entries_) {
        auto first = slots_.end();
        for (auto it = slots_.begin(); it != slots_.end(); ++it)
            if (it->second.requests == 0 && (first == slots_.end() || it->second.expires < first->second.expires))
                first = it;
        if (first == slots_.end()) break;
        slots_.erase(first);
    }
    slots_.emplace(key, Slot{std::move(entry), nullptr, now + ttl_, 0});
    return kUploadPrefix + key;
}

UploadTable::Slots::iterator UploadTable::find(std::string_view target, Clock::time_point now) {
    target = target.substr(0, target.find('?'));
    const std::string_view prefix = kUploadPrefix;
    if (target.substr(0, prefix.size()) != prefix) return slots_.end();
    auto it = slots_.find(target.substr(prefix.size()));
    if (it == slots_.end()) return it;
    if (it->second.requests == 0 && it->second.expires <= now) return slots_.end();
    return it;
}

std::optional<UploadCheckout> UploadTable::begin(std::string_view target, Clock::time_point now) {
    std::lock_guard lock(mutex_);
    auto it = find(target, now);
    if (it == slots_.end()) return std::nullopt;
    ++it->second.requests;
    return UploadCheckout{it->first, it->second.entry, it->second.sink};
}

std::shared_ptr<UploadSink> UploadTable::keep_sink(const UploadCheckout& checkout, std::shared_ptr<UploadSink> sink) {
    std::lock_guard lock(mutex_);
    auto it = slots_.find(checkout.key);
    if (it == slots_.end()) return sink;
    if (!it->second.sink) it->second.sink = std::move(sink);
    return it->second.sink;
}

void UploadTable::end(const UploadCheckout& checkout, UploadEnd how, Clock::time_point now) {
    std::lock_guard lock(mutex_);
    auto it = slots_.find(checkout.key);
    if (it == slots_.end()) return;
    if (it->second.requests > 0) --it->second.requests;
    if (how != UploadEnd::broken) {
        slots_.erase(it);
        return;
    }
    it->second.expires = now + ttl_;
}

std::vector<AbandonedUpload> UploadTable::take_abandoned(Clock::time_point now) {
    std::vector<AbandonedUpload> out;
    std::lock_guard lock(mutex_);
    for (auto it = slots_.begin(); it != slots_.end();) {
        if (it->second.sink && it->second.requests == 0 && it->second.expires <= now) {
            out.push_back({std::move(it->second.entry), it->second.sink->received()});
            it = slots_.erase(it);
        } else {
            ++it;
        }
    }
    return out;
}

std::optional<UploadTable::Clock::time_point> UploadTable::next_abandon() const {
    std::optional<Clock::time_point> next;
    std::lock_guard lock(mutex_);
    for (const auto& [key, slot] : slots_)
        if (slot.sink && slot.requests == 0 && (!next || slot.expires < *next)) next = slot.expires;
    return next;
}

std::size_t UploadTable::size() const {
    std::lock_guard lock(mutex_);
    return slots_.size();
}

}  // namespace umf::provider
