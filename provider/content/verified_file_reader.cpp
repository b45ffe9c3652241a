#include "provider/content/verified_file_reader.hpp"

#include <algorithm>
#include <cstdlib>
#include <chrono>
#include <new>

namespace umf::provider {

namespace {

// A piece is read, hashed and encrypted whole; checkpoints (every
// native::HashCheckpoints::kStep bytes) fall on piece boundaries.
constexpr std::size_t kPieceBytes = 1 << 20;
// Pieces in flight: memory stays at a few megabytes whatever the file's size.
constexpr std::size_t kPieces = 8;
// How often a reader waiting on a slow connection looks at its lease: a
// program opening the file for writing waits at most about this long.
constexpr std::chrono::milliseconds kLeaseLook{5};
static_assert(native::HashCheckpoints::kStep % kPieceBytes == 0);

}  // namespace

void VerifiedFileReader::Free::operator()(char* p) const { std::free(p); }

VerifiedFileReader::VerifiedFileReader(const VerifiedFileBody::value_type& body, std::function<void()> ready)
    : body_(body), ready_(std::move(ready)) {
    for (std::size_t i = 0; i < kPieces; ++i) {
        buffers_.emplace_back(static_cast<char*>(std::malloc(kPieceBytes)));
        if (!buffers_.back()) throw std::bad_alloc();
        free_.push_back(buffers_.back().get());
    }
    thread_ = std::thread([this] { run(); });
}

VerifiedFileReader::~VerifiedFileReader() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    freed_.notify_all();
    thread_.join();
}

VerifiedFileReader::Next VerifiedFileReader::take(Piece& piece, boost::beast::error_code& ec) {
    std::lock_guard lock(mutex_);
    if (!ready_pieces_.empty()) {
        piece = ready_pieces_.front();
        ready_pieces_.pop_front();
        taken_ = piece.data;
        return Next::piece;
    }
    if (failure_) {
        ec = failure_;
        return Next::failed;
    }
    if (read_all_) return Next::end;
    taker_waits_ = true;
    return Next::waiting;
}

void VerifiedFileReader::release() {
    {
        std::lock_guard lock(mutex_);
        if (!taken_) return;
        free_.push_back(const_cast<char*>(taken_));
        taken_ = nullptr;
    }
    freed_.notify_all();
}

char* VerifiedFileReader::free_buffer(ReadLease* lease) {
    std::unique_lock lock(mutex_);
    while (!stopping_ && free_.empty()) {
        if (!lease || !lease->held()) {
            freed_.wait(lock);
            continue;
        }
        // A slow phone must not keep a program that saves the file waiting.
        freed_.wait_for(lock, kLeaseLook);
        if (!lease->unbroken()) lease->release();
    }
    if (stopping_) return nullptr;
    char* buffer = free_.back();
    free_.pop_back();
    return buffer;
}

void VerifiedFileReader::give_back(char* buffer) {
    {
        std::lock_guard lock(mutex_);
        free_.push_back(buffer);
    }
    freed_.notify_all();
}

void VerifiedFileReader::publish(const Piece* piece, boost::beast::error_code ec, bool end) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        if (piece) ready_pieces_.push_back(*piece);
        if (ec) failure_ = ec;
        if (end) read_all_ = true;
        wake = std::exchange(taker_waits_, false);
    }
    if (wake) ready_();
}

void VerifiedFileReader::run() {
    std::uint64_t at = body_.offset();
    if (ReadLease lease = body_.unchanged_under_lease(); lease.held()) {
        const auto stopped_at = read_leased(lease, at);
        if (!stopped_at || *stopped_at == body_.file_size()) return;
        at = *stopped_at;
    }
    read_hashed(at);
}

std::optional<std::uint64_t> VerifiedFileReader::read_leased(ReadLease& lease, std::uint64_t at) {
    const std::uint64_t size = body_.file_size();
    if (at >= size) {
        publish(nullptr, {}, true);
        return size;
    }
    while (at < size) {
        char* buffer = free_buffer(&lease);
        if (!buffer) return std::nullopt;
        if (!lease.held()) {
            give_back(buffer);
            return at;
        }
        const long n = read_piece(at, buffer);
        if (n <= 0) return std::nullopt;
        at += static_cast<std::uint64_t>(n);
        // Read before the lease is given back, the piece is the hashed bytes.
        const Piece piece{buffer, static_cast<std::size_t>(n)};
        publish(&piece, {}, at == size);
        if (!lease.unbroken()) {
            lease.release();
            return at;
        }
    }
    return at;
}

long VerifiedFileReader::read_piece(std::uint64_t at, char* buffer) {
    // Pieces end on multiples of kPieceBytes, so the checkpoints' offsets
    // are reached exactly wherever the transfer began.
    const std::uint64_t size = body_.file_size();
    const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(size - at, kPieceBytes - at % kPieceBytes));
    boost::beast::error_code ec;
    const long n = body_.read_at(at, buffer, want, ec);
    // None: shorter than when it was offered.
    if (n <= 0) publish(nullptr, n < 0 ? ec : boost::beast::error_code(DownloadCheck::changed), false);
    return n;
}

void VerifiedFileReader::read_hashed(std::uint64_t at) {
    boost::beast::error_code ec;
    char* scratch = free_buffer();
    if (!scratch) return;
    auto hash = body_.hasher_at(at, scratch, kPieceBytes, ec);
    give_back(scratch);
    if (!hash) return publish(nullptr, ec, false);
    const std::uint64_t size = body_.file_size();
    if (at >= size) return publish(nullptr, {}, true);
    while (at < size) {
        char* buffer = free_buffer();
        if (!buffer) return;
        const long n = read_piece(at, buffer);
        if (n <= 0) return;
        at += static_cast<std::uint64_t>(n);
        if (!body_.hash_piece(*hash, buffer, static_cast<std::size_t>(n), at, ec)) return publish(nullptr, ec, false);
        const Piece piece{buffer, static_cast<std::size_t>(n)};
        publish(&piece, {}, at == size);
    }
}

}  // namespace umf::provider
