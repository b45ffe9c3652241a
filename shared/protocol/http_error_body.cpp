#include "shared/protocol/http_error_body.hpp"

#include <nlohmann/json.hpp>

namespace umf::protocol {

std::string encode_error_body(const Error& error) { return "{\"messages\":[" + encode(error) + "]}"; }

std::optional<Error> parse_error_body(std::string_view body) {
    if (body.size() > kMaxReplyBytes) return std::nullopt;
    // The envelope is two levels around the message's own.
    bool too_deep = false;
    nlohmann::json::parser_callback_t watch_depth = [&too_deep](int depth, nlohmann::json::parse_event_t event,
                                                                nlohmann::json&) {
        if ((event == nlohmann::json::parse_event_t::object_start ||
             event == nlohmann::json::parse_event_t::array_start) &&
            depth + 1 > kMaxDepth + 2)
            too_deep = true;
        return !too_deep;
    };
    const auto json = nlohmann::json::parse(body.begin(), body.end(), watch_depth, false);
    if (too_deep) return std::nullopt;
    if (json.is_discarded() || !json.is_object()) return std::nullopt;
    const auto messages = json.find("messages");
    if (messages == json.end() || !messages->is_array() || messages->size() != 1) return std::nullopt;
    const auto parsed = parse_message((*messages)[0].dump(), kRequesterLimits);
    const auto* message = std::get_if<Message>(&parsed);
    const auto* error = message ? std::get_if<Error>(message) : nullptr;
    if (!error) return std::nullopt;
    return *error;
}

}  // namespace umf::protocol
