#include "native/hashing_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <new>
#include <stdexcept>

namespace umf::native {

namespace {

// Written back behind the writer in steps of this much.
constexpr std::uint64_t kWritebackBytes = 8 << 20;

}  // namespace

HashingWriter::HashingWriter(int fd, std::size_t piece_bytes, bool direct, std::size_t pieces)
    : fd_(fd), direct_wanted_(direct) {
    const std::size_t rounded = (piece_bytes + kDirectAlign - 1) / kDirectAlign * kDirectAlign;
    for (std::size_t i = 0; i < pieces; ++i) {
        buffers_.emplace_back(static_cast<char*>(std::aligned_alloc(kDirectAlign, rounded)));
        if (!buffers_.back()) throw std::bad_alloc();
        free_.push_back({buffers_.back().get(), piece_bytes, i});
    }
    holders_.assign(pieces, 0);
    hashing_.thread = std::thread([this] { run(hashing_, &HashingWriter::hash_piece); });
    writing_.thread = std::thread([this] { run(writing_, &HashingWriter::write_piece); });
}

bool HashingWriter::set_direct(bool on) {
    if (on == direct_now_) return true;
    const int flags = ::fcntl(fd_, F_GETFL);
    if (flags < 0 || ::fcntl(fd_, F_SETFL, on ? flags | O_DIRECT : flags & ~O_DIRECT) != 0) return false;
    direct_now_ = on;
    return true;
}

std::string HashingWriter::write_at_end(const char* data, std::size_t size) {
    const bool aligned = written_ % kDirectAlign == 0 && size % kDirectAlign == 0 &&
                         reinterpret_cast<std::uintptr_t>(data) % kDirectAlign == 0;
    if (direct_wanted_ && !set_direct(aligned)) direct_wanted_ = false;  // not on this file system
    while (size > 0) {
        const ssize_t n = ::write(fd_, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno == EINVAL && direct_now_) {
            // The file system takes O_DIRECT but not with this alignment: through the cache from now on.
            direct_wanted_ = false;
            if (!set_direct(false)) return std::strerror(errno);
            continue;
        }
        if (n <= 0) return std::strerror(n < 0 ? errno : ENOSPC);
        data += n;
        size -= static_cast<std::size_t>(n);
        written_ += static_cast<std::uint64_t>(n);
    }
    if (!direct_now_ && written_ - written_back_ >= kWritebackBytes) {
        // Only a hint: where the file system has no such call, fsync does it all at the end.
        ::sync_file_range(fd_, static_cast<off64_t>(written_back_), static_cast<off64_t>(written_ - written_back_),
                          SYNC_FILE_RANGE_WRITE);
        written_back_ = written_;
    }
    if (direct_now_) written_back_ = written_;
    return {};
}

HashingWriter::~HashingWriter() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    hashing_.thread.join();
    writing_.thread.join();
}

void HashingWriter::rethrow_failure() const {
    if (!failure_.empty()) throw std::runtime_error(failure_);
}

HashingWriter::Piece HashingWriter::next() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !free_.empty() || !failure_.empty(); });
    rethrow_failure();
    const Piece piece = free_.back();
    free_.pop_back();
    return piece;
}

void HashingWriter::submit(Piece piece, std::size_t size) {
    {
        std::lock_guard lock(mutex_);
        holders_[piece.slot] = 2;
        hashing_.queued.emplace_back(piece, size);
        writing_.queued.emplace_back(piece, size);
    }
    changed_.notify_all();
}

void HashingWriter::drain() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] {
        const auto idle = [](const Lane& lane) { return lane.queued.empty() && !lane.busy; };
        return (idle(hashing_) && idle(writing_)) || !failure_.empty();
    });
    rethrow_failure();
}

void HashingWriter::restart() {
    std::lock_guard lock(mutex_);
    if (::ftruncate(fd_, 0) != 0 || ::lseek(fd_, 0, SEEK_SET) != 0)
        throw std::runtime_error(std::string("cannot empty the file: ") + std::strerror(errno));
    sha_ = std::make_unique<native::Sha256>();
    hashed_ = written_ = written_back_ = 0;
}

std::string HashingWriter::hex() {
    std::lock_guard lock(mutex_);
    return sha_->hex();
}

std::unique_ptr<native::Sha256> HashingWriter::hash_so_far() const {
    std::lock_guard lock(mutex_);
    return sha_->copy();
}

void HashingWriter::continue_from(std::uint64_t at, std::unique_ptr<native::Sha256> state,
                                  native::HashCheckpoints* checkpoints) {
    std::lock_guard lock(mutex_);
    sha_ = std::move(state);
    hashed_ = at;
    checkpoints_ = checkpoints;
}

void HashingWriter::hash_piece(const char* data, std::size_t size) {
    sha_->update(data, size);
    // Saved where a piece ends on a step: a caller whose pieces end on
    // multiples of their size, a divisor of the step, meets every one.
    hashed_ += size;
    if (checkpoints_ && hashed_ % native::HashCheckpoints::kStep == 0) checkpoints_->save(hashed_, *sha_);
}

void HashingWriter::write_piece(const char* data, std::size_t size) {
    if (fd_ < 0) return;
    const std::string error = write_at_end(data, size);
    if (error.empty()) return;
    std::lock_guard lock(mutex_);
    if (failure_.empty()) failure_ = "cannot write the file: " + error;
}

void HashingWriter::run(Lane& lane, void (HashingWriter::*work)(const char*, std::size_t)) {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return stopping_ || !lane.queued.empty(); });
        if (lane.queued.empty()) return;  // stopping, nothing left
        auto [piece, size] = lane.queued.front();
        lane.queued.pop_front();
        lane.busy = true;
        // After a failed write nothing more is hashed or written; the pieces only come back.
        if (!failure_.empty()) size = 0;
        lock.unlock();
        if (size > 0) (this->*work)(piece.data, size);
        lock.lock();
        lane.busy = false;
        if (--holders_[piece.slot] == 0) free_.push_back(piece);
        changed_.notify_all();
    }
}

}  // namespace umf::native
