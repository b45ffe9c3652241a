// The body of every error answer the provider gives over HTTP (downloads,
// uploads, the HTTPS transport, requests it cannot read): the HTTPS
// transport's envelope holding one `error` message,
//   {"messages":[{"type":"error","v":1,"code":"not_found","message":"..."}]}
// (docs/PROTOCOL.md, "Errors over HTTP"). One writer for the provider, one
// reader for the requesters, so a reason given at the screen reaches the
// person holding the phone.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "shared/protocol/messages.hpp"

namespace umf::protocol {

std::string encode_error_body(const Error& error);

// The error an HTTP answer's body carries, or nullopt when the body is not
// that envelope (an empty body, a proxy's page, a message of another type).
std::optional<Error> parse_error_body(std::string_view body);

}  // namespace umf::protocol
