// Where an upload's bytes go (docs/PROTOCOL.md, "Upload"): a hidden private
// temporary file in the put folder (".umf-put-XXXXXX", created exclusively,
// 0600), hashed as the bytes come; only when all of them arrived and match
// the put's SHA-256 is it linked under its name, never over an existing
// file ("report (1).pdf" when "report.pdf" exists). Anything else removes
// it. Free of sockets: the connection feeds it. An upload that broke off
// keeps its sink (the bytes so far and their hash state) for a later request
// to go on from received(); each request claims the sink first, and a newer
// claim supersedes an older request that is still writing (a connection the
// provider has not yet seen die). Thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "native/hashing_writer.hpp"
#include "shared/protocol/error_codes.hpp"

namespace umf::provider {

class UploadError : public std::runtime_error {
public:
    UploadError(protocol::ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    protocol::ErrorCode code() const { return code_; }

private:
    protocol::ErrorCode code_;
};

inline constexpr const char* kUploadTempPrefix = ".umf-put-";

// Links `temp` (in `dir`) under the first free numbered name and removes the
// temporary name; returns the name used. Never replaces a file. Throws
// UploadError (internal).
std::string store_without_overwriting(const std::filesystem::path& temp, const std::filesystem::path& dir,
                                      const std::string& name);

// The free bytes of the file system that holds `dir` for an unprivileged
// user; nullopt when it cannot be told.
std::optional<std::uintmax_t> free_bytes(const std::filesystem::path& dir);

class UploadSink {
public:
    // Checks that `folder` has room for `size` bytes (too_large) and creates
    // the temporary file there (internal when it cannot). `sha256` empty:
    // named later (expect_sha256()).
    UploadSink(const std::filesystem::path& folder, std::int64_t size, std::string sha256);
    ~UploadSink();
    UploadSink(const UploadSink&) = delete;
    UploadSink& operator=(const UploadSink&) = delete;

    // A request takes the sink over: its claim, and the bytes held then.
    struct Claim {
        std::uint64_t claim = 0;
        std::int64_t received = 0;
    };
    Claim claim();
    // More bytes from the request holding `claim` (0: a sink nobody has
    // claimed, written by whoever made it). Throws UploadError:
    // interrupted beyond `size` or when a newer claim took over (superseded()
    // says which), internal when the disk refuses them.
    void write(const void* data, std::size_t size, std::uint64_t claim = 0);
    bool superseded(std::uint64_t claim) const;
    std::int64_t received() const;
    // The SHA-256 of the bytes received so far (a resumed request's
    // Upload-Prefix-SHA256 is checked against it). Throws UploadError
    // internal when the disk refused them.
    std::string received_sha256();
    std::int64_t size() const { return size_; }
    // The SHA-256 the bytes must have: whether it is known, and naming it
    // when it is not (64 hex digits, any case). Throws UploadError
    // bad_request when it was known and this is another.
    bool knows_sha256() const;
    void expect_sha256(const std::string& hex);
    // Every byte arrived and matches: stored under `name` or a numbered one,
    // returned. Throws UploadError interrupted (too few bytes, another hash)
    // or internal; the temporary file is gone either way.
    std::string store(const std::string& name, std::uint64_t claim = 0);
    // Removes the temporary file (the destructor does the same).
    void discard();
    const std::filesystem::path& temp_path() const { return temp_; }

private:
    std::filesystem::path folder_;
    std::filesystem::path temp_;
    int fd_ = -1;
    std::int64_t size_ = 0;
    std::int64_t received_ = 0;
    std::string sha256_;
    // Hashes and writes the bytes on a thread of its own, large files past
    // the page cache (native/hashing_writer.hpp); the piece being filled.
    std::unique_ptr<native::HashingWriter> writer_;
    native::HashingWriter::Piece piece_;
    std::size_t piece_filled_ = 0;
    bool done_ = false;
    std::uint64_t claim_ = 0;
    mutable std::mutex mutex_;

    void discard_locked();
    // The filled part of the piece to the writer; then waits until all is
    // written. Throws UploadError internal when the disk refused it.
    void flush_locked();
};

}  // namespace umf::provider
