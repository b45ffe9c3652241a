// What is shown at a screen point. The provider asks its resolvers in order
// (board items, shared items, the window under the point, a snapshot); the
// first answer wins (docs/ARCHITECTURE.md, "Content").
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/common/screen_point.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

// Aims only ask what a grab would take and must stay cheap (no snapshot is
// made, no file hashed); a grab asks for the content itself.
enum class Purpose { preview, grab };

// What a resolver found. `file` and `bytes` are the provider's own: a path
// the provider resolved itself (never one a requester sent), or bytes made
// for this grab (a snapshot PNG).
struct Resolved {
    protocol::ContentKind kind = protocol::ContentKind::none;
    std::string title;                   // what the requester shows
    std::string url;                     // kind url
    std::optional<std::filesystem::path> file;  // kind file
    std::shared_ptr<const std::string> bytes;   // kind snapshot (grab only)
    std::string name;                    // file name to offer: kind file, snapshot
    std::string mime;                    // kind file, snapshot
};

class Resolver {
public:
    virtual ~Resolver() = default;
    // For logs: "board", "shared", "x11-window", "snapshot".
    virtual const char* name() const = 0;
    // nullopt: nothing of this resolver's at the point; ask the next one.
    // Thread-safe: sessions call it concurrently. Throws only on a failure
    // worth reporting (the requester gets `internal`).
    virtual std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const = 0;
};

}  // namespace umf::provider
