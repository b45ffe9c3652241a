// SHA-256 states of a file at every kStep bytes, saved while it is hashed,
// so the hash of its first N bytes costs at most kStep bytes of reading.
// The provider saves them while a download hashes the file as it sends it:
// a resumed download (HTTP Range from offset N) starts its hasher from the
// last state at or before N, and still checks the whole file against the
// announced SHA-256 before sending the last piece, without reading the
// whole file again. The requester saves them while it hashes a file to put:
// a resumed upload tells the provider the SHA-256 of the bytes it should
// hold. Thread-safe: transfers of one link share it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "native/sha256.hpp"

namespace umf::native {

class HashCheckpoints {
public:
    static constexpr std::uint64_t kStep = 64ull << 20;

    // The hasher's state after the file's first `offset` bytes (a multiple
    // of kStep; others are not kept).
    void save(std::uint64_t offset, const Sha256& state);

    // The latest saved state at or before `offset`, copied, and where it
    // is; (0, a new hasher) when there is none.
    std::pair<std::uint64_t, std::unique_ptr<Sha256>> nearest(std::uint64_t offset) const;

    // A hasher that has taken the file's first `offset` bytes: the nearest
    // state, then the bytes from there, asked of `read(at, into, size)`
    // (how many it read; 0 or less when the file ends or fails there) into
    // `buffer`. Null when `read` gave none before `offset`.
    using Read = std::function<long(std::uint64_t at, char* into, std::size_t size)>;
    std::unique_ptr<Sha256> hasher_at(std::uint64_t offset, const Read& read, char* buffer,
                                      std::size_t buffer_size) const;

private:
    mutable std::mutex mutex_;
    std::map<std::uint64_t, std::unique_ptr<Sha256>> states_;
};

}  // namespace umf::native
