#include "native/hash_checkpoints.hpp"

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

}  // namespace umf::native
