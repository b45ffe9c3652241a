#include "provider/discovery/nearby_routes.hpp"

#include <memory>
#include <string>

#include "provider/net/http_response_headers.hpp"
#include "shared/field/field_io.hpp"

namespace umf::provider {

namespace http = boost::beast::http;

namespace {

void answer(HttpExchange& exchange, const HttpRequest& req, std::string body, bool any_origin) {
    auto res = std::make_shared<http::response<http::string_body>>(http::status::ok, req.version());
    set_common_headers(*res);
    res->set(http::field::content_type, "application/json");
    // Both change: a screen comes or goes, the field follows the screens.
    res->set(http::field::cache_control, "no-store");
    if (any_origin) res->set(http::field::access_control_allow_origin, "*");
    res->keep_alive(req.keep_alive());
    const std::size_t size = body.size();
    if (req.method() == http::verb::get) res->body() = std::move(body);
    res->prepare_payload();
    if (req.method() == http::verb::head) res->content_length(size);
    write_response(exchange, std::move(res));
}

}  // namespace

void serve_nearby(HttpExchange& exchange, const HttpRequest& req, const NearbyScreens* screens) {
    answer(exchange, req, nearby_json(screens ? screens->list() : std::vector<NearbyScreen>{}), false);
}

void serve_field(HttpExchange& exchange, const HttpRequest& req, const protocol::FieldInfo& field) {
    answer(exchange, req, field_to_json(field.definition), true);
}

}  // namespace umf::provider
