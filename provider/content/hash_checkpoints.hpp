// SHA-256 states of a file at every kStep bytes, saved while a download
// hashes the file as it sends it. A resumed download (HTTP Range from
// offset N) starts its hasher from the last state at or before N and reads
// at most kStep bytes to reach N, so it still checks the whole file against
// the announced SHA-256 before sending the last piece, without reading the
// whole file again. Thread-safe: transfers of one link share it.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "native/sha256.hpp"

namespace umf::provider {

class HashCheckpoints {
public:
    static constexpr std::uint64_t kStep = 64ull << 20;

    // The hasher's state after the file's first `offset` bytes (a multiple
    // of kStep; others are not kept).
    void save(std::uint64_t offset, const native::Sha256& state);

    // The latest saved state at or before `offset`, copied, and where it
    // is; (0, a new hasher) when there is none.
    std::pair<std::uint64_t, std::unique_ptr<native::Sha256>> nearest(std::uint64_t offset) const;

private:
    mutable std::mutex mutex_;
    std::map<std::uint64_t, std::unique_ptr<native::Sha256>> states_;
};

}  // namespace umf::provider
