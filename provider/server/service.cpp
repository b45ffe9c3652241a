#include "server/service.hpp"

#include <unistd.h>

#include <climits>
#include <stdexcept>
#include <type_traits>

#include "field/default_field.hpp"
#include "field/field_io.hpp"
#include "overlay/preset.hpp"
#include "server/pairing.hpp"

#ifndef UMF_PROVIDER_VERSION
#define UMF_PROVIDER_VERSION "0.0.0"
#endif

namespace umf::provider {

namespace p = protocol;

ServiceConfig default_service_config(int screen_width_px, int screen_height_px, const std::string& screen_name) {
    ServiceConfig c;
    char host[HOST_NAME_MAX + 1] = {};
    c.provider.name = ::gethostname(host, sizeof host - 1) == 0 && host[0] ? host : "umf-provider";
    c.provider.software = std::string("umf-provider/") + UMF_PROVIDER_VERSION;

    const DefaultField choice = default_field_for_screen(screen_width_px, screen_height_px);
    c.field.definition = load_field(std::string(UMF_DATA_DIR) + "/fields/" + choice.file);
    p::Screen screen;
    screen.name = screen_name;
    screen.region = {0.0, 0.0, static_cast<double>(c.field.definition.width),
                     static_cast<double>(c.field.definition.height)};
    screen.width_px = screen_width_px;
    screen.height_px = screen_height_px;
    c.field.screens.push_back(screen);

    const auto presets = overlay::built_in_presets();
    const overlay::Preset* balanced = overlay::find_preset(presets, "balanced");
    if (!balanced) throw std::logic_error("the built-in preset \"balanced\" is missing");
    c.overlay = p::overlay_info(*balanced);
    c.limits = p::Limits{};
    return c;
}

Service::Service(ServiceConfig config, std::string token) : config_(std::move(config)), token_(std::move(token)) {}

void Service::set_token(std::string token) {
    std::lock_guard lock(token_mutex_);
    token_ = std::move(token);
}

bool Service::token_matches(std::string_view token) const {
    std::lock_guard lock(token_mutex_);
    return !token_.empty() && tokens_equal(token, token_);
}

Outcome Service::handle_text(SessionState& state, std::string_view text) const {
    // Parsing checks the size before anything else.
    p::ParseLimits limits;
    limits.max_bytes = static_cast<std::size_t>(config_.limits.max_message_bytes);
    return handle(state, p::parse_message(text, limits));
}

Outcome Service::handle_binary(SessionState& state) const {
    Outcome out;
    out.replies.push_back(p::Error{std::nullopt, p::ErrorCode::bad_request, "binary frames are not accepted"});
    out.close = !state.welcomed;
    return out;
}

Outcome Service::handle(SessionState& state, const p::ParseResult& parsed) const {
    Outcome out;
    if (const auto* error = std::get_if<p::ProtocolError>(&parsed)) {
        out.replies.push_back(p::to_error(*error));
        out.close = !state.welcomed;
        return out;
    }
    const p::Message& message = std::get<p::Message>(parsed);

    if (!state.welcomed) {
        const auto* hello = std::get_if<p::Hello>(&message);
        if (!hello) {
            out.replies.push_back(p::Error{std::nullopt, p::ErrorCode::unauthorized,
                                           std::string("a session starts with hello, not ") + p::type_name(message)});
            out.close = true;
            return out;
        }
        if (!token_matches(hello->token)) {
            out.replies.push_back(p::Error{hello->id, p::ErrorCode::unauthorized, "unknown pairing token"});
            out.close = true;
            return out;
        }
        state.welcomed = true;
        out.replies.push_back(p::Welcome{hello->id, config_.provider, config_.field, config_.overlay, config_.limits});
        return out;
    }

    std::visit(
        [&](const auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, p::Seeking>) {
                // No reply. The overlay's on-demand activation comes later.
            } else if constexpr (std::is_same_v<T, p::Aim>) {
                // Resolvers come later: a screen is there, nothing to take.
                out.replies.push_back(p::Target{m.id, m.point, p::ContentKind::none, ""});
            } else if constexpr (std::is_same_v<T, p::Grab>) {
                p::Content content;
                content.id = m.id;
                content.kind = p::ContentKind::none;
                out.replies.push_back(std::move(content));
            } else if constexpr (std::is_same_v<T, p::Hello>) {
                out.replies.push_back(p::Error{m.id, p::ErrorCode::bad_request, "this session is already welcomed"});
            } else {
                out.replies.push_back(p::Error{std::nullopt, p::ErrorCode::bad_request,
                                               std::string("\"") + p::type_name(message) +
                                                   "\" is a provider's message, not a request"});
            }
        },
        message);
    return out;
}

}  // namespace umf::provider
