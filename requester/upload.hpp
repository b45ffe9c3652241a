// Sending a put's file over its HTTPS upload link (docs/PROTOCOL.md,
// "Upload"), pinned like the session: `PUT /up/...` with Content-Length,
// the bytes streamed from the file in pieces (never all in memory), and the
// provider's answer, the put_status "done", read back. A connection that
// breaks goes on from what the provider holds (HEAD, then PUT with
// Upload-Offset), with backoff, while that grows. A put that left its
// SHA-256 out has the bytes hashed as they go, and the hash named after
// them (Upload-SHA256): the file is read once.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "native/hash_checkpoints.hpp"
#include "requester/pinned_tls.hpp"
#include "shared/protocol/messages.hpp"
#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

struct UploadRequest {
    std::string path;                 // the put_status's "upload": "/up/..."
    std::filesystem::path file;       // read from the start, `size` bytes
    std::int64_t size = 0;            // as announced in the put
    // The states of the hash the put announced (file_digest.hpp); with them
    // a resumed request says the SHA-256 of the bytes the provider should
    // hold (Upload-Prefix-SHA256), and a file changed since is refused then.
    std::shared_ptr<const native::HashCheckpoints> checkpoints;
    // The put left its sha256 out: it is taken as the bytes are sent and
    // named after them.
    bool hash_after = false;
};

struct Uploaded {
    protocol::PutStatus status;  // done
    std::string sha256;          // named after the bytes (hash_after), else empty
};

// Called now and then while bytes go out: sent so far, of size.
using UploadProgress = std::function<void(std::int64_t sent, std::int64_t size)>;

// Returns the provider's put_status (status done). Throws GrabFailure:
// "input" (exit 3) when the file cannot be read or changed its size, or
// (hash_after) changed while it was sent,
// "certificate" for another certificate, "input" also when a resumed
// request found the provider's bytes other than the file's start (it
// changed while it was sent), "upload" when the transfer broke
// off and nothing more reached the provider for timeouts.download_idle,
// and the provider's code for an answer it explains ("interrupted",
// "too_large", "not_found", "bad_request"). `notice` hears of each resume.
Uploaded upload_file(const protocol::PairingUrl& provider, const UploadRequest& request,
                     const UploadProgress& progress = {}, const NetTimeouts& timeouts = {},
                     const std::function<void(const std::string&)>& notice = {});

}  // namespace umf::requester
