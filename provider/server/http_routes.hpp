// The provider's HTTP routes, one table for the whole server. Some take a
// request once its header is read and read its body themselves (an upload
// streams to a file); the others get it whole. Each route's handler lives
// beside its feature and answers through the HttpExchange the session lends
// it; the HTTPS transport (/api/) is the session's own.
#pragma once

#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/parser.hpp>
#include <functional>
#include <memory>

#include "common/http_exchange.hpp"
#include "server/route_table.hpp"
#include "server/service.hpp"

namespace umf::provider {

class HttpSession;

// The WebSocket path (docs/PROTOCOL.md, "Transport"): any upgrade request
// is taken for it before the routes are asked.
inline constexpr const char* kWebSocketPath = "/ws";
// The HTTPS transport's paths start so (docs/PROTOCOL.md, "HTTPS transport").
inline constexpr const char* kApiPrefix = "/api/";

using HeaderRoute =
    std::function<void(HttpSession& session, boost::beast::http::request_parser<boost::beast::http::empty_body>&&)>;
using RequestRoute = std::function<void(HttpSession& session, const HttpRequest& req)>;

struct HttpRoutes {
    RouteTable<HeaderRoute> on_header;
    // A request no route takes is answered 405: only GET and HEAD are
    // served outside /api/.
    RouteTable<RequestRoute> on_request;
};

// Uploads (PUT /up/...), the share target (POST /share), the HTTPS transport
// (/api/...), downloads (GET or HEAD /dl/...), the nearby screens and this
// screen's field (/nearby.json, /field.json) and the web client's files.
std::shared_ptr<const HttpRoutes> make_http_routes(std::shared_ptr<const Service> service);

}  // namespace umf::provider
