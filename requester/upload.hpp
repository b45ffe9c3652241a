// Sending a put's file over its HTTPS upload link (docs/PROTOCOL.md,
// "Upload"), pinned like the session: `PUT /up/...` with Content-Length,
// the bytes streamed from the file in pieces (never all in memory), and the
// provider's answer, the put_status "done", read back. A connection that
// breaks goes on from what the provider holds (HEAD, then PUT with
// Upload-Offset), with backoff, while that grows.
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
};

// Called now and then while bytes go out: sent so far, of size.
using UploadProgress = std::function<void(std::int64_t sent, std::int64_t size)>;

// Returns the provider's put_status (status done). Throws GrabFailure:
// "input" (exit 3) when the file cannot be read or changed its size,
// "certificate" for another certificate, "input" also when a resumed
// request found the provider's bytes other than the file's start (it
// changed while it was sent), "upload" when the transfer broke
// off and nothing more reached the provider for timeouts.download_idle,
// and the provider's code for an answer it explains ("interrupted",
// "too_large", "not_found", "bad_request"). `notice` hears of each resume.
protocol::PutStatus upload_file(const protocol::PairingUrl& provider, const UploadRequest& request,
                                const UploadProgress& progress = {}, const NetTimeouts& timeouts = {},
                                const std::function<void(const std::string&)>& notice = {});

}  // namespace umf::requester
