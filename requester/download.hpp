// Fetching a grabbed file over its one-time HTTPS link (docs/PROTOCOL.md,
// "Downloads"), with the same certificate pin as the session. The bytes go
// to a private temporary file in the target directory and are checked
// (Content-Length, size, SHA-256) while they stream; only a complete, checked
// file gets a real name, and never one that already exists. A connection
// that breaks is asked again for the rest (HTTP Range with If-Range), with
// backoff, while that brings new bytes; on any failure nothing is left
// behind.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "requester/pinned_tls.hpp"
#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

struct DownloadRequest {
    std::string path;                   // the content's "download": "/dl/..."
    std::string name;                   // the content's "name", cleaned again here
    std::int64_t size = 0;              // the content's "size"
    std::optional<std::string> sha256;  // checked when given
};

struct SavedFile {
    std::filesystem::path path;  // absolute
    std::string name;            // the name it got: the cleaned name, or "name (n).ext"
    std::int64_t size = 0;
    std::string sha256;          // of the bytes received
};

// Creates `dir` when missing. Throws GrabFailure: "output" (exit 3) for the
// directory or the file, "connection"/"certificate" for the network,
// the provider's code ("not_found", "too_large", "internal") for an HTTP
// error it explains, "download" for a short, long or corrupt transfer.
// `progress` hears of each resume ("the connection was lost at 410.0 MB of
// 1073.7 MB (...); resuming in 250 ms"). It gives up when nothing new has
// arrived for timeouts.download_idle.
SavedFile download_file(const protocol::PairingUrl& provider, const DownloadRequest& request, const std::filesystem::path& dir,
                        const NetTimeouts& timeouts = {},
                        const std::function<void(const std::string&)>& progress = {});

// Links (or renames without replacing) the finished temporary file at
// `temp` to `name`, or "name (1)", "name (2)"... in `dir`, whichever is free
// first; the temporary name is gone afterwards. Returns the name used.
// Throws GrabFailure "output" when none can be made.
std::string store_without_overwriting(const std::filesystem::path& temp, const std::filesystem::path& dir,
                                      const std::string& name);

}  // namespace umf::requester
