// What the HTTP connection lends a route for one request (net/http_routes.hpp):
// the stream to answer on or read a body from, the bytes already read past
// the header, the one error answer, and what follows a response. A route
// lives beside its feature (content/download_route.hpp, put/upload_route.hpp)
// and knows nothing of the server beyond this. Everything here is called on
// the connection's strand, where the stream's handlers run too.
#pragma once

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/status.hpp>
#include <boost/beast/http/string_body.hpp>
#include <memory>
#include <optional>
#include <string>

#include "provider/net/response_write.hpp"
#include "provider/net/tls_stream.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

// A request read whole (its body at most 16 KiB).
using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;

class HttpExchange {
public:
    virtual ~HttpExchange() = default;

    virtual TlsStream& stream() = 0;
    virtual boost::beast::flat_buffer& buffer() = 0;
    // Keeps the connection while the handle is held: a route's pending
    // handlers hold it.
    virtual std::shared_ptr<HttpExchange> hold() = 0;
    // The server is stopping: a route starts nothing more.
    virtual bool stopping() const = 0;
    // The usual 30 s again, for an answer after a long body.
    virtual void restart_timeout() = 0;
    // A JSON answer, under the timeout already running.
    virtual void answer_json(int status, bool keep_alive, std::string body) = 0;
    // Every error answer: its status and the one error body
    // (protocol/http_error_body.hpp); without keep_alive the connection
    // ends once it is written, lingering for what the peer still sends.
    virtual void answer_error(boost::beast::http::status status, bool keep_alive, const protocol::Error& error,
                              const char* allow = nullptr) = 0;
    void answer_error(boost::beast::http::status status, bool keep_alive, protocol::ErrorCode code,
                      const std::string& message, const char* allow = nullptr) {
        answer_error(status, keep_alive, protocol::Error{std::nullopt, code, message}, allow);
    }
    // A response the route wrote itself is out: the next request is read,
    // or the connection ends.
    virtual void written(bool keep_alive) = 0;
    // Drops the connection at once (the peer must get nothing more).
    virtual void drop() = 0;
};

// Writes `response`, then goes on as its keep-alive says. A failed write
// ends the connection: the peer went away mid-response.
template <class Body>
void write_response(HttpExchange& exchange, std::shared_ptr<boost::beast::http::response<Body>> response) {
    const bool keep_alive = response->keep_alive();
    auto& res = *response;
    send_response(exchange.stream(), res,
                  [held = exchange.hold(), response = std::move(response), keep_alive](boost::beast::error_code ec) {
                      if (ec) return;
                      held->written(keep_alive);
                  });
}

}  // namespace umf::provider
