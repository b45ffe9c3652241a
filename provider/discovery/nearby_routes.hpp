// What a phone page needs to tell which screen it sees when it is not its
// own (docs/PROTOCOL.md, "Nearby screens"), served without a token: the
// screens announced nearby, and this screen's field for the pages of other
// screens. Neither is a secret: the one is on the network, the other on
// the screen.
#pragma once

#include "provider/discovery/nearby_screens.hpp"
#include "provider/net/http_exchange.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

inline constexpr const char* kNearbyPath = "/nearby.json";
inline constexpr const char* kFieldPath = "/field.json";

// GET or HEAD /nearby.json: nearby_json of the list (null: an empty one),
// for this screen's own page.
void serve_nearby(HttpExchange& exchange, const HttpRequest& req, const NearbyScreens* screens);
// GET or HEAD /field.json: the field shown now, as a field file
// (umf-field/1), readable by a page of any origin.
void serve_field(HttpExchange& exchange, const HttpRequest& req, const protocol::FieldInfo& field);

}  // namespace umf::provider
