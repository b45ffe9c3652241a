// The wire message parser (shared/protocol/messages.hpp) on any bytes, with
// the requester's limits (a welcome may carry a whole field) and the
// provider's. What parses is encoded again, as a provider answers, and what
// encode() returns must parse: its documented promise.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

#include "shared/protocol/messages.hpp"

namespace p = umf::protocol;

namespace {

void reencode(const p::Message& message) {
    std::string text;
    try {
        text = p::encode(message);
    } catch (const std::invalid_argument&) {
        return;  // a value encode() refuses to send, which a peer may still send
    }
    if (!std::holds_alternative<p::Message>(p::parse_message(text, p::kRequesterLimits))) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    for (const p::ParseLimits& limits : {p::kRequesterLimits, p::ParseLimits{}}) {
        const p::ParseResult parsed = p::parse_message(text, limits);
        if (const auto* message = std::get_if<p::Message>(&parsed)) {
            (void)p::type_name(*message);
            (void)p::is_request(*message);
            reencode(*message);
        } else {
            // What the provider answers a text that did not parse.
            reencode(p::to_error(std::get<p::ProtocolError>(parsed)));
        }
        // Below the provider's cap both limits read the same text the same way.
        if (size > p::kMaxRequestBytes) break;
    }
    return 0;
}
