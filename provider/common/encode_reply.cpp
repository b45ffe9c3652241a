#include "provider/common/encode_reply.hpp"

#include <exception>
#include <optional>
#include <variant>

namespace umf::provider {

namespace p = protocol;

std::string encode_reply(const p::Message& message) {
    try {
        return p::encode(message);
    } catch (const std::exception&) {
        std::optional<p::RequestId> id;
        std::visit(
            [&](const auto& m) {
                if constexpr (requires { m.id; }) id = m.id;
            },
            message);
        return p::encode(p::Error{id, p::ErrorCode::internal, "cannot encode the reply"});
    }
}

}  // namespace umf::provider
