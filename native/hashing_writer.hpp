// The pieces of a large transfer hashed and written on threads of their
// own (the requester's downloads, the provider's uploads), so the thread
// that reads the network only decrypts. Hashing and writing each have a
// thread: a write waits for the disk without using the processor, and
// done after the hash on one thread it would add its time to the hash's
// (on this kind of machine about 0.4 s and 0.5 s per GiB). A few pieces
// are in flight at most (memory stays flat whatever the file's size).
//
// Given no file (fd -1), it only hashes: the requester's put, whose
// sending thread reads and encrypts while the hash is taken beside it.
//
// A large file is written with O_DIRECT where the file system takes it:
// straight from the piece to the disk, without a copy into the page cache
// (which on this kind of machine costs from 0.2 to 2.6 s per GiB depending on
// how warm the memory it gets is) and without pushing the user's cached
// files out for a file that will not be read soon. Pieces that are not
// aligned to kDirectAlign (the last one, the first after a cut) go through
// the page cache, and the kernel is asked to write those back as they
// come, so the final fsync has little left to do.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "native/hash_checkpoints.hpp"
#include "native/sha256.hpp"

namespace umf::native {

class HashingWriter {
public:
    struct Piece {
        char* data = nullptr;
        std::size_t capacity = 0;
        std::size_t slot = 0;  // the writer's own
    };

    // Offsets and sizes written directly are multiples of this; pieces are
    // allocated aligned to it.
    static constexpr std::size_t kDirectAlign = 4096;

    // Writes to `fd` (owned by the caller, open while this lives; -1: no
    // file, the pieces are only hashed) from its current offset, `pieces`
    // pieces of `piece_bytes` each; directly when `direct` and the file
    // system allows it.
    HashingWriter(int fd, std::size_t piece_bytes, bool direct, std::size_t pieces = 6);
    ~HashingWriter();
    HashingWriter(const HashingWriter&) = delete;
    HashingWriter& operator=(const HashingWriter&) = delete;

    // A free piece to fill; waits while every piece is queued. Throws the
    // writer's error (std::runtime_error naming it) once it has failed.
    Piece next();
    // Queues the piece `next` gave with its first `size` bytes filled.
    void submit(Piece piece, std::size_t size);
    // Waits until every queued piece is hashed and written; throws the
    // writer's error as next() does.
    void drain();
    // After drain(): starts the file and the hash again from nothing (a
    // download the provider sent again from its first byte).
    void restart();
    // After drain(): the SHA-256 of everything written (the hasher is used up).
    std::string hex();
    // After drain(): a hasher in the state of everything written so far,
    // to go on from apart from this writer's.
    std::unique_ptr<native::Sha256> hash_so_far() const;
    // After drain(): the hash goes on from `state`, the hash of the first
    // `at` bytes, and saves its state into `checkpoints` (when given) at
    // every HashCheckpoints::kStep bytes from the start (a resumed put's).
    void continue_from(std::uint64_t at, std::unique_ptr<native::Sha256> state,
                       native::HashCheckpoints* checkpoints = nullptr);

private:
    struct Free {
        void operator()(char* p) const { std::free(p); }
    };
    // One of the two threads a piece goes through, in the order submitted.
    struct Lane {
        std::deque<std::pair<Piece, std::size_t>> queued;  // oldest first
        bool busy = false;                                 // its thread holds a piece
        std::thread thread;
    };

    // A lane's thread: `work` on each piece, then the piece is let go.
    void run(Lane& lane, void (HashingWriter::*work)(const char*, std::size_t));
    void hash_piece(const char* data, std::size_t size);
    void write_piece(const char* data, std::size_t size);
    void rethrow_failure() const;
    // Writes at the file's end; the reason when it could not.
    std::string write_at_end(const char* data, std::size_t size);
    // Sets or clears O_DIRECT; false when the file system refuses it.
    bool set_direct(bool on);

    int fd_;
    bool direct_wanted_;
    bool direct_now_ = false;
    std::vector<std::unique_ptr<char, Free>> buffers_;
    std::unique_ptr<native::Sha256> sha_ = std::make_unique<native::Sha256>();
    std::uint64_t hashed_ = 0;          // bytes hashed, counted from continue_from's `at`
    native::HashCheckpoints* checkpoints_ = nullptr;
    std::uint64_t written_ = 0;         // bytes written to the file
    std::uint64_t written_back_ = 0;    // bytes handed to the kernel's writeback

    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<Piece> free_;
    std::vector<int> holders_;  // of each slot: the lanes that still have it
    Lane hashing_;
    Lane writing_;
    bool stopping_ = false;
    std::string failure_;
};

}  // namespace umf::native
