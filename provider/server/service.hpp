// The provider's answers to requester messages, independent of sockets (so
// unit tests drive it directly): docs/PROTOCOL.md, "Session". A session calls
// handle_text or handle_binary per received frame and sends the replies in
// order; `close` says to close the WebSocket afterwards.
#pragma once

#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "protocol/messages.hpp"

namespace umf::provider {

struct ServiceConfig {
    protocol::ProviderInfo provider;
    protocol::FieldInfo field;
    protocol::OverlayInfo overlay;
    protocol::Limits limits;
};

// The shipped default field for one screen of the given size, covering the
// whole field (portrait screens are not turned yet), the `balanced` preset,
// the protocol's default limits and this host's name. Throws when the field
// file cannot be loaded.
ServiceConfig default_service_config(int screen_width_px = 1920, int screen_height_px = 1080,
                                     const std::string& screen_name = "screen");

// What one connection has established so far.
struct SessionState {
    bool welcomed = false;
};

struct Outcome {
    std::vector<protocol::Message> replies;
    bool close = false;  // close the WebSocket (policy violation, 1008) after sending the replies
};

class Service {
public:
    Service(ServiceConfig config, std::string token);

    // One text frame. Before the welcome: a hello with the token gets the
    // welcome, anything else an error and `close`. After it: seeking gets
    // nothing, aim a target, grab a content, anything malformed or not a
    // request an error; the session is never closed.
    Outcome handle_text(SessionState& state, std::string_view text) const;
    // A binary frame: bad_request (and `close` before the welcome).
    Outcome handle_binary(SessionState& state) const;
    // A parsed frame (what handle_text does after parsing).
    Outcome handle(SessionState& state, const protocol::ParseResult& parsed) const;

    // Replaces the token; sessions already welcomed stay.
    void set_token(std::string token);
    const ServiceConfig& config() const { return config_; }

private:
    bool token_matches(std::string_view token) const;

    ServiceConfig config_;
    mutable std::mutex token_mutex_;
    std::string token_;
};

}  // namespace umf::provider
