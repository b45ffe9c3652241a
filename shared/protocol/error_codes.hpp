// The error codes of protocol version 1 and their names on the wire.
#pragma once

#include <optional>
#include <string_view>

namespace umf::protocol {

// A closed set within a protocol version: a new code needs a new version,
// so a requester can handle every code it may receive. The exceptions are
// refused and interrupted, added with puts (docs/PROTOCOL.md, "Put"): they
// answer only a put, which only a requester that knows them sends, so an
// older requester never receives them.
enum class ErrorCode {
    bad_request,          // malformed, unknown type, out-of-range field, unexpected message
    unauthorized,         // wrong or revoked pairing token, or any request before a welcome
    rate_limited,         // more aims or grabs than the welcome's limits allow
    not_found,            // no screen shows that field point, or an unknown or used download
    too_large,            // message above max_message_bytes, or content above the download limit
    internal,             // the provider failed resolving or serving; the request may be retried
    unsupported_version,  // "v" is not a version this side speaks
    refused,              // a put: dismissed at the screen, not answered in time, or puts are off
    interrupted,          // a put's upload: ended early or its bytes did not match its sha256
};

inline constexpr ErrorCode kAllErrorCodes[] = {
    ErrorCode::bad_request, ErrorCode::unauthorized, ErrorCode::rate_limited,       ErrorCode::not_found,
    ErrorCode::too_large,   ErrorCode::internal,     ErrorCode::unsupported_version, ErrorCode::refused,
    ErrorCode::interrupted,
};

constexpr const char* to_string(ErrorCode code) {
    switch (code) {
        case ErrorCode::bad_request: return "bad_request";
        case ErrorCode::unauthorized: return "unauthorized";
        case ErrorCode::rate_limited: return "rate_limited";
        case ErrorCode::not_found: return "not_found";
        case ErrorCode::too_large: return "too_large";
        case ErrorCode::internal: return "internal";
        case ErrorCode::unsupported_version: return "unsupported_version";
        case ErrorCode::refused: return "refused";
        case ErrorCode::interrupted: return "interrupted";
    }
    return "internal";
}

constexpr std::optional<ErrorCode> error_code_from_string(std::string_view name) {
    for (ErrorCode c : kAllErrorCodes)
        if (name == to_string(c)) return c;
    return std::nullopt;
}

}  // namespace umf::protocol
