// The HTTP routes a server answers, one table for the whole server. Some take
// a request once its header is read and read its body themselves (an upload
// streams to a file); the others get it whole. Each route's handler lives
// beside its feature and answers through the HttpExchange the connection
// lends it. The WebSocket (/ws) and the HTTPS transport (/api/) are the
// connection's own and come before any route.
#pragma once

#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/parser.hpp>
#include <functional>

#include "provider/net/http_exchange.hpp"
#include "provider/net/route_table.hpp"

namespace umf::provider {

// The WebSocket path (docs/PROTOCOL.md, "Transport"): any upgrade request
// is taken for it.
inline constexpr const char* kWebSocketPath = "/ws";
// The HTTPS transport's paths start so (docs/PROTOCOL.md, "HTTPS transport").
inline constexpr const char* kApiPrefix = "/api/";

using HeaderRoute =
    std::function<void(HttpExchange& exchange, boost::beast::http::request_parser<boost::beast::http::empty_body>&&)>;
using RequestRoute = std::function<void(HttpExchange& exchange, const HttpRequest& req)>;

struct HttpRoutes {
    RouteTable<HeaderRoute> on_header;
    // A request no route takes is answered 405: only GET and HEAD are
    // served outside /api/.
    RouteTable<RequestRoute> on_request;
};

}  // namespace umf::provider
