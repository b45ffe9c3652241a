#include "provider/put/upload_sink.hpp"

#include <fcntl.h>
#include <openssl/evp.h>
#include <stdio.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "shared/io/store_file.hpp"

namespace umf::provider {

namespace fs = std::filesystem;
using protocol::ErrorCode;

namespace {

std::string errno_text() { return std::strerror(errno); }

// The umask without changing it (umask(2) would, for a moment, for every
// thread of the server): Linux reports it in /proc/self/status.
mode_t process_umask() {
    FILE* f = std::fopen("/proc/self/status", "re");
    mode_t mask = 022;
    if (!f) return mask;
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
        unsigned value = 0;
        if (std::sscanf(line, "Umask: %o", &value) == 1) {
            mask = static_cast<mode_t>(value & 0777);
            break;
        }
    }
    std::fclose(f);
    return mask;
}

}  // namespace

std::string store_without_overwriting(const fs::path& temp, const fs::path& dir, const std::string& name) {
    try {
        return io::store_under_free_name(temp, dir, name);
    } catch (const std::runtime_error& e) {
        throw UploadError(ErrorCode::internal, e.what());
    }
}

std::optional<std::uintmax_t> free_bytes(const fs::path& dir) {
    struct statvfs st {};
    if (::statvfs(dir.c_str(), &st) != 0) return std::nullopt;
    return static_cast<std::uintmax_t>(st.f_bavail) * st.f_frsize;
}

namespace {

// Pieces handed to the writer; uploads from kDirectFromBytes go past the page cache.
constexpr std::size_t kPieceBytes = 1 << 20;
constexpr std::int64_t kDirectFromBytes = std::int64_t{64} << 20;

}  // namespace

UploadSink::UploadSink(const fs::path& folder, std::int64_t size, std::string sha256)
    : folder_(folder), size_(size), sha256_(std::move(sha256)) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    const auto room = free_bytes(folder_);
    if (!room) throw UploadError(ErrorCode::internal, "cannot use the folder " + folder_.string() + ": " + errno_text());
    if (size_ < 0 || static_cast<std::uintmax_t>(size_) > *room)
        throw UploadError(ErrorCode::too_large, std::to_string(size_) + " bytes do not fit: " + std::to_string(*room) +
                                                    " bytes are free");
    std::string tmpl = (folder_ / (std::string(kUploadTempPrefix) + "XXXXXX")).string();
    fd_ = ::mkostemp(tmpl.data(), O_CLOEXEC);  // O_EXCL, 0600
    if (fd_ < 0) throw UploadError(ErrorCode::internal, "cannot create a file in " + folder_.string() + ": " + errno_text());
    temp_ = tmpl;
    // A small upload gets pieces of its own size and two of them; a large
    // one eight of 1 MiB, queued between the connection and the disk.
    const auto piece_bytes = static_cast<std::size_t>(std::clamp<std::int64_t>(size_, 4096, kPieceBytes));
    const std::size_t pieces = size_ > 4 * static_cast<std::int64_t>(kPieceBytes) ? 8 : 2;
    writer_ = std::make_unique<native::HashingWriter>(fd_, piece_bytes, size_ >= kDirectFromBytes, pieces);
}

UploadSink::~UploadSink() { discard_locked(); }

void UploadSink::discard() {
    std::lock_guard lock(mutex_);
    discard_locked();
}

UploadSink::Claim UploadSink::claim() {
    std::lock_guard lock(mutex_);
    return {++claim_, received_};
}

bool UploadSink::superseded(std::uint64_t claim) const {
    std::lock_guard lock(mutex_);
    return claim != claim_;
}

std::int64_t UploadSink::received() const {
    std::lock_guard lock(mutex_);
    return received_;
}

bool UploadSink::knows_sha256() const {
    std::lock_guard lock(mutex_);
    return !sha256_.empty();
}

void UploadSink::expect_sha256(const std::string& hex) {
    std::string lower = hex;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    std::lock_guard lock(mutex_);
    if (sha256_.empty()) {
        sha256_ = std::move(lower);
        return;
    }
    if (lower != sha256_)
        throw UploadError(ErrorCode::bad_request, "Upload-SHA256 " + lower + " is not the put's sha256 " + sha256_);
}

std::string UploadSink::received_sha256() {
    std::lock_guard lock(mutex_);
    if (done_) throw UploadError(ErrorCode::internal, "the upload is over");
    try {
        // The pieces handed over, then the one being filled.
        writer_->drain();
        auto hash = writer_->hash_so_far();
        if (piece_.data) hash->update(piece_.data, piece_filled_);
        return hash->hex();
    } catch (const std::runtime_error& e) {
        throw UploadError(ErrorCode::internal, std::string("cannot write the upload: ") + e.what());
    }
}

void UploadSink::discard_locked() {
    writer_.reset();  // before the file it writes to is closed
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!done_ && !temp_.empty()) ::unlink(temp_.c_str());
    done_ = true;
}

void UploadSink::write(const void* data, std::size_t size, std::uint64_t claim) {
    std::lock_guard lock(mutex_);
    if (claim != claim_) throw UploadError(ErrorCode::interrupted, "a newer request goes on with the upload");
    if (done_) throw UploadError(ErrorCode::internal, "the upload is over");
    if (static_cast<std::int64_t>(size) > size_ - received_)
        throw UploadError(ErrorCode::interrupted, "more bytes than the put's size");
    const char* p = static_cast<const char*>(data);
    std::size_t left = size;
    try {
        while (left > 0) {
            if (!piece_.data) piece_ = writer_->next();
            const std::size_t n = std::min(left, piece_.capacity - piece_filled_);
            std::memcpy(piece_.data + piece_filled_, p, n);
            piece_filled_ += n;
            p += n;
            left -= n;
            if (piece_filled_ == piece_.capacity) {
                writer_->submit(piece_, piece_filled_);
                piece_ = {};
                piece_filled_ = 0;
            }
        }
    } catch (const std::runtime_error& e) {
        throw UploadError(ErrorCode::internal, std::string("cannot write the upload: ") + e.what());
    }
    received_ += static_cast<std::int64_t>(size);
}

void UploadSink::flush_locked() {
    try {
        if (piece_.data && piece_filled_ > 0) writer_->submit(piece_, piece_filled_);
        piece_ = {};
        piece_filled_ = 0;
        writer_->drain();
    } catch (const std::runtime_error& e) {
        throw UploadError(ErrorCode::internal, std::string("cannot write the upload: ") + e.what());
    }
}

std::string UploadSink::store(const std::string& name, std::uint64_t claim) {
    std::lock_guard lock(mutex_);
    if (claim != claim_) throw UploadError(ErrorCode::interrupted, "a newer request goes on with the upload");
    if (done_) throw UploadError(ErrorCode::internal, "the upload is over");
    struct Discard {
        UploadSink* sink;
        ~Discard() { sink->discard_locked(); }
    } discard_on_exit{this};
    if (received_ != size_)
        throw UploadError(ErrorCode::interrupted, "the upload ended after " + std::to_string(received_) + " of " +
                                                      std::to_string(size_) + " bytes");
    if (sha256_.empty()) throw UploadError(ErrorCode::interrupted, "the upload's SHA-256 was never named");
    flush_locked();
    const std::string digest = writer_->hex();
    if (digest != sha256_)
        throw UploadError(ErrorCode::interrupted,
                          "the bytes' SHA-256 is " + digest + ", not the put's " + sha256_ + "; nothing was kept");
    // The permissions of a file the user saved: 0600 only kept others out
    // while it was incomplete.
    if (::fchmod(fd_, 0666 & ~process_umask()) != 0 || ::fsync(fd_) != 0)
        throw UploadError(ErrorCode::internal, "cannot finish the upload: " + errno_text());
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) throw UploadError(ErrorCode::internal, "cannot finish the upload: " + errno_text());
    std::string stored = store_without_overwriting(temp_, folder_, name);
    done_ = true;  // the temporary name is gone: nothing to remove
    return stored;
}

}  // namespace umf::provider
