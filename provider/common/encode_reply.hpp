// A message as the provider sends it (over the WebSocket, the HTTPS transport
// or an upload's answer): encoded, or an internal error with the request's id
// when a resolver produced something out of range.
#pragma once

#include <string>

#include "shared/protocol/messages.hpp"

namespace umf::provider {

std::string encode_reply(const protocol::Message& message);

}  // namespace umf::provider
