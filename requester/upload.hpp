// Sending a put's file over its one-time HTTPS link (docs/PROTOCOL.md,
// "Upload"), pinned like the session: `PUT /up/...` with Content-Length,
// the bytes streamed from the file in pieces (never all in memory), and the
// provider's answer, the put_status "done", read back.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "requester/pinned_tls.hpp"
#include "shared/protocol/messages.hpp"
#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

struct UploadRequest {
    std::string path;                 // the put_status's "upload": "/up/..."
    std::filesystem::path file;       // read from the start, `size` bytes
    std::int64_t size = 0;            // as announced in the put
};

// Called now and then while bytes go out: sent so far, of size.
using UploadProgress = std::function<void(std::int64_t sent, std::int64_t size)>;

// Returns the provider's put_status (status done). Throws GrabFailure:
// "input" (exit 3) when the file cannot be read or changed its size,
// "connection"/"certificate" for the network, "upload" when the transfer
// broke off or stalled, and the provider's code for an answer it explains
// ("interrupted", "too_large", "not_found", "bad_request").
protocol::PutStatus upload_file(const protocol::PairingUrl& provider, const UploadRequest& request,
                                const UploadProgress& progress = {}, const NetTimeouts& timeouts = {});

}  // namespace umf::requester
