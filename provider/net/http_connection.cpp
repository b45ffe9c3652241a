#include "provider/net/http_connection.hpp"

#include <boost/asio/post.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <limits>

#include "provider/net/http_framing.hpp"
#include "provider/net/http_response_headers.hpp"
#include "provider/net/lingering_close.hpp"
#include "provider/net/listener.hpp"
#include "provider/net/websocket_connection.hpp"
#include "shared/protocol/http_error_body.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;

HttpConnection::HttpConnection(TlsStream&& stream, beast::flat_buffer&& buffer, std::string peer,
                               std::shared_ptr<const MessageHandler> handler, std::shared_ptr<ConnectionRegistry> registry,
                               std::shared_ptr<ApiSessions> api_sessions, std::shared_ptr<const HttpRoutes> routes)
    : executor_(stream.get_executor()),
      stream_(std::move(stream)),
      handler_(std::move(handler)),
      registry_(std::move(registry)),
      api_sessions_(std::move(api_sessions)),
      routes_(std::move(routes)),
      buffer_(std::move(buffer)),
      peer_(std::move(peer)),
      timer_(executor_) {}

HttpConnection::~HttpConnection() {
    if (poll_pending_ && api_sessions_) api_sessions_->cancel_poll(poll_ticket_);
    if (registry_) registry_->remove(this);
}

void HttpConnection::run() { read_request(); }

void HttpConnection::read_request() {
    // Also the idle timeout of a kept-alive connection.
    beast::get_lowest_layer(stream_).expires_after(kHttpTimeout);
    request_.reset();
    header_.emplace();
    header_->header_limit(kMaxRequestHeaderBytes);
    // The body's limit depends on the route: an upload's is its put's size,
    // anything else's kMaxRequestBodyBytes (on_header). Not boost::none:
    // Beast 1.74 compares the length with the optional, and none is less
    // than every length.
    header_->body_limit(std::numeric_limits<std::uint64_t>::max());
    buffer_.max_size(kMaxRequestHeaderBytes + kMaxRequestBodyBytes);
    http::async_read_header(stream_, buffer_, *header_,
                            beast::bind_front_handler(&HttpConnection::on_header, shared_from_this()));
}

void HttpConnection::request_failed(beast::error_code ec) {
    // A request that is not HTTP or too large gets its status; a
    // connection gone or timed out, nothing.
    if (ec == http::error::header_limit || ec == http::error::buffer_overflow)
        answer_error(http::status::request_header_fields_too_large, false, protocol::ErrorCode::too_large,
                     "the request's header is larger than " + std::to_string(kMaxRequestHeaderBytes) + " bytes");
    else if (ec == http::error::body_limit)
        answer_error(http::status::payload_too_large, false, protocol::ErrorCode::too_large,
                     "the body is larger than " + std::to_string(kMaxRequestBodyBytes) + " bytes");
    else if (ec.category() == http::make_error_code(http::error::bad_method).category() &&
             ec != http::error::end_of_stream && ec != http::error::partial_message)
        answer_error(http::status::bad_request, false, protocol::ErrorCode::bad_request,
                     "a request that cannot be read: " + ec.message());
}

void HttpConnection::on_header(beast::error_code ec, std::size_t) {
    if (closing_) return;
    if (ec) {
        request_failed(ec);
        return;
    }
    if (const auto why = ambiguous_framing(header_->get().version(), header_->get())) {
        // Never served, never read on: the connection ends with the answer.
        answer_error(http::status::bad_request, false, protocol::ErrorCode::bad_request, *why);
        return;
    }
    const beast::string_view target = header_->get().target();
    if (const auto* route =
            routes_->on_header.find(header_->get().method(), std::string_view(target.data(), target.size()))) {
        // The route reads the body, if it wants it.
        (*route)(*this, std::move(*header_));
        header_.reset();
        return;
    }
    // A declared length is checked here; a chunked body chunk by chunk.
    if (const auto length = header_->content_length(); length && *length > kMaxRequestBodyBytes) {
        request_failed(http::error::body_limit);
        return;
    }
    request_.emplace(std::move(*header_));
    header_.reset();
    request_->body_limit(kMaxRequestBodyBytes);
    if (request_->is_done()) {
        // No body: nothing more to read.
        net::post(executor_, [self = shared_from_this()] { self->on_request({}, 0); });
        return;
    }
    http::async_read(stream_, buffer_, *request_,
                     beast::bind_front_handler(&HttpConnection::on_request, shared_from_this()));
}

void HttpConnection::on_request(beast::error_code ec, std::size_t) {
    if (closing_) return;
    if (ec) {
        request_failed(ec);
        return;
    }
    buffer_.max_size(std::numeric_limits<std::size_t>::max());
    const auto& req = request_->get();
    const beast::string_view target = req.target();
    if (websocket::is_upgrade(req)) {
        if (target.substr(0, target.find('?')) != kWebSocketPath) {
            answer_error(http::status::not_found, false, protocol::ErrorCode::not_found,
                         std::string("the WebSocket is at ") + kWebSocketPath);
            return;
        }
        upgrade(req);
        return;
    }
    if (target.starts_with(kApiPrefix)) {
        // Any method: each API path says which one it takes.
        serve_api(req);
        return;
    }
    if (const auto* route = routes_->on_request.find(req.method(), std::string_view(target.data(), target.size()))) {
        (*route)(*this, req);
        return;
    }
    answer_error(http::status::method_not_allowed, req.keep_alive(), protocol::ErrorCode::bad_request,
                 "only GET and HEAD are served here; POST only under /api/");
}

void HttpConnection::upgrade(const HttpRequest& req) {
    handed_on_ = true;
    auto ws = std::make_shared<WebSocketConnection>(std::move(stream_), std::move(buffer_), std::move(peer_), handler_,
                                                    registry_);
    registry_->hand_over(this, ws.get(), ws);
    next_ = ws;
    ws->run(req);
}

void HttpConnection::restart_timeout() { beast::get_lowest_layer(stream_).expires_after(kHttpTimeout); }

void HttpConnection::answer_json(int status, bool keep_alive, std::string body) {
    api_response(status, keep_alive, std::move(body));
}

void HttpConnection::api_response(int status, bool keep_alive, std::string body, const char* allow) {
    auto res = std::make_shared<http::response<http::string_body>>(static_cast<http::status>(status), 11);
    set_common_headers(*res);
    res->set(http::field::content_type, "application/json");
    res->set(http::field::cache_control, "no-store");
    if (allow) res->set(http::field::allow, allow);
    res->keep_alive(keep_alive);
    res->body() = std::move(body);
    res->prepare_payload();
    write_response(std::move(res));
}

void HttpConnection::answer_error(http::status status, bool keep_alive, const protocol::Error& error,
                               const char* allow) {
    if (!keep_alive) {
        restart_timeout();
        linger_after_response_ = true;
    }
    api_response(static_cast<int>(status), keep_alive, protocol::encode_error_body(error), allow);
}

void HttpConnection::drop() { beast::get_lowest_layer(stream_).close(); }

template <class Body>
void HttpConnection::write_response(std::shared_ptr<http::response<Body>> response) {
    const bool keep_alive = response->keep_alive();
    auto& res = *response;
    response_ = std::move(response);
    send_response(stream_, res, [self = shared_from_this(), keep_alive](beast::error_code ec) {
        self->response_.reset();
        if (ec) return;  // the peer went away mid-response; the session ends and frees what it held
        self->after_response(keep_alive);
    });
}

void HttpConnection::after_response(bool keep_alive) {
    if (watching_) {
        // After a long poll a read is under way already: it becomes the next
        // request once the client sends one, within the idle timeout. TLS
        // cannot shut down with a read outstanding, so an end is a plain close.
        if (keep_alive && !closing_) {
            resume_after_watch_ = true;
            arm_timer(kHttpTimeout, &HttpConnection::on_idle_timer);
        } else {
            drop();
        }
        return;
    }
    if (keep_alive && !closing_) {
        read_request();
        return;
    }
    if (linger_after_response_) {
        lingering_close(beast::get_lowest_layer(stream_), shared_from_this());
        return;
    }
    end_tls();
}

void HttpConnection::end_tls() {
    beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(5));
    stream_.async_shutdown([self = shared_from_this()](beast::error_code) {
        beast::error_code ignored;
        beast::get_lowest_layer(self->stream_).socket().shutdown(net::ip::tcp::socket::shutdown_both, ignored);
    });
}

void HttpConnection::shutdown() {
    net::post(executor_, [self = shared_from_this()] { self->do_shutdown(); });
}

void HttpConnection::do_shutdown() {
    // Asked before the upgrade reached the strand: the WebSocket session stops.
    if (handed_on_) {
        if (auto next = next_.lock()) next->shutdown();
        return;
    }
    closing_ = true;
    // An open long poll is answered (the provider goes away: 1001), then the
    // connection closes; a response to a request read whole ends the
    // connection once written; anything else (a request being read, an
    // upload, a connection idle after a poll) is simply dropped.
    if (poll_pending_) {
        api_sessions_->cancel_poll(poll_ticket_);
        finish_poll(poll_serial_, {200, api_body({}, {}, kClosedGoingAway), false});
    } else if (!request_ || !request_->is_done() || (watching_ && !response_)) {
        drop();
    }
}

void HttpConnection::abort() {
    net::post(executor_, [self = shared_from_this()] {
        if (self->handed_on_) {
            if (auto next = self->next_.lock()) next->abort();
            return;
        }
        self->closing_ = true;
        self->drop();
    });
}

}  // namespace umf::provider
