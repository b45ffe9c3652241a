// Where an upload's bytes go (docs/PROTOCOL.md, "Upload"): a hidden private
// temporary file in the put folder (".umf-put-XXXXXX", created exclusively,
// 0600), hashed as the bytes come; only when all of them arrived and match
// the put's SHA-256 is it linked under its name, never over an existing
// file ("report (1).pdf" when "report.pdf" exists). Anything else removes
// it. Free of sockets: the connection feeds it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

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
    // the temporary file there (internal when it cannot).
    UploadSink(const std::filesystem::path& folder, std::int64_t size, std::string sha256);
    ~UploadSink();
    UploadSink(const UploadSink&) = delete;
    UploadSink& operator=(const UploadSink&) = delete;

    // More bytes. Throws UploadError: interrupted beyond `size`, internal
    // when the disk refuses them.
    void write(const void* data, std::size_t size);
    std::int64_t received() const { return received_; }
    // Every byte arrived and matches: stored under `name` or a numbered one,
    // returned. Throws UploadError interrupted (too few bytes, another hash)
    // or internal; the temporary file is gone either way.
    std::string store(const std::string& name);
    // Removes the temporary file (the destructor does the same).
    void discard();
    const std::filesystem::path& temp_path() const { return temp_; }

private:
    struct Hash;
    std::filesystem::path folder_;
    std::filesystem::path temp_;
    int fd_ = -1;
    std::int64_t size_ = 0;
    std::int64_t received_ = 0;
    std::string sha256_;
    std::unique_ptr<Hash> hash_;
    bool done_ = false;
};

}  // namespace umf::provider
