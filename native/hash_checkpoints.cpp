#include "native/hash_checkpoints.hpp"

#include <algorithm>

namespace umf::native {

void HashCheckpoints::save(std::uint64_t offset, const Sha256& state) {
    if (offset == 0 || offset % kStep != 0) return;
    auto twin = state.copy();
    std::lock_guard lock(mutex_);
    states_.try_emplace(offset, std::move(twin));
}

std::pair<std::uint64_t, std::unique_ptr<Sha256>> HashCheckpoints::nearest(std::uint64_t offset) const {
    std::lock_guard lock(mutex_);
    auto it = states_.upper_bound(offset);
    if (it == states_.begin()) return {0, std::make_unique<Sha256>()};
    --it;
    return {it->first, it->second->copy()};
}

std::unique_ptr<Sha256> HashCheckpoints::hasher_at(std::uint64_t offset, const Read& read, char* buffer,
                                                   std::size_t buffer_size) const {
    auto [at, hash] = nearest(offset);
    while (at < offset) {
        const long n = read(at, buffer, static_cast<std::size_t>(std::min<std::uint64_t>(offset - at, buffer_size)));
        if (n <= 0) return nullptr;
        hash->update(buffer, static_cast<std::size_t>(n));
        at += static_cast<std::uint64_t>(n);
    }
    return std::move(hash);
}

}  // namespace umf::native
