#include "server/session.hpp"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <exception>
#include <stdexcept>

#include "server/listener.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
namespace ssl = boost::asio::ssl;

namespace {

constexpr auto kHandshakeTimeout = std::chrono::seconds(30);
constexpr std::size_t kMaxRequestHeaderBytes = 8 * 1024;
// Replies waiting beyond this stop the reading until the peer takes them.
constexpr std::size_t kMaxQueuedReplies = 64;

std::string encode_reply(const protocol::Message& message) {
    try {
        return protocol::encode(message);
    } catch (const std::exception& e) {
        // A resolver produced something out of range; the requester gets an
        // internal error with the request's id instead.
        std::optional<protocol::RequestId> id;
        std::visit(
            [&](const auto& m) {
                if constexpr (requires { m.id; }) id = m.id;
            },
            message);
        return protocol::encode(protocol::Error{id, protocol::ErrorCode::internal, "cannot encode the reply"});
    }
}

}  // namespace

Session::Session(net::ip::tcp::socket&& socket, ssl::context& tls, std::shared_ptr<const Service> service,
                 std::shared_ptr<SessionRegistry> registry)
    : ws_(std::move(socket), tls), service_(std::move(service)), registry_(std::move(registry)) {}

Session::~Session() {
    if (registry_) registry_->remove(this);
}

void Session::run() {
    registry_->add(this, weak_from_this());
    net::dispatch(ws_.get_executor(), [self = shared_from_this()] {
        if (self->closing_) return;
        beast::get_lowest_layer(self->ws_).expires_after(kHandshakeTimeout);
        self->ws_.next_layer().async_handshake(ssl::stream_base::server,
                                               beast::bind_front_handler(&Session::on_tls_handshake, self));
    });
}

void Session::on_tls_handshake(beast::error_code ec) {
    if (ec || closing_) return;
    beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
    request_.header_limit(kMaxRequestHeaderBytes);
    request_.body_limit(0);
    http::async_read(ws_.next_layer(), buffer_, request_,
                     beast::bind_front_handler(&Session::on_request, shared_from_this()));
}

void Session::on_request(beast::error_code ec, std::size_t) {
    if (closing_) return;
    if (ec) {
        // A request that is not HTTP gets a 400; a connection gone or timed out, nothing.
        if (ec.category() == http::make_error_code(http::error::bad_method).category() &&
            ec != http::error::end_of_stream)
            reject(http::status::bad_request, "bad request\n");
        return;
    }
    const auto& req = request_.get();
    if (!websocket::is_upgrade(req)) {
        reject(http::status::not_found, "not found\n");
        return;
    }
    const beast::string_view target = req.target();
    if (target.substr(0, target.find('?')) != kWebSocketPath) {
        reject(http::status::not_found, "not found\n");
        return;
    }
    beast::get_lowest_layer(ws_).expires_never();
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::server, "umf-provider"); }));
    ws_.read_message_max(static_cast<std::size_t>(service_->config().limits.max_message_bytes));
    ws_.async_accept(req, beast::bind_front_handler(&Session::on_accept, shared_from_this()));
}

void Session::reject(http::status status, const char* text) {
    response_ = std::make_shared<http::response<http::string_body>>(status, 11);
    response_->set(http::field::server, "umf-provider");
    response_->set(http::field::content_type, "text/plain; charset=utf-8");
    response_->keep_alive(false);
    response_->body() = text;
    response_->prepare_payload();
    beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
    http::async_write(ws_.next_layer(), *response_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
        if (ec) return;
        beast::get_lowest_layer(self->ws_).expires_after(std::chrono::seconds(5));
        self->ws_.next_layer().async_shutdown([self](beast::error_code) {
            beast::error_code ignored;
            beast::get_lowest_layer(self->ws_).socket().shutdown(net::ip::tcp::socket::shutdown_both, ignored);
        });
    });
}

void Session::on_accept(beast::error_code ec) {
    if (ec) return;
    websocket_ = true;
    if (closing_) {
        if (!close_started_) close(close_code_);
        return;
    }
    read();
}

void Session::read() {
    reading_ = true;
    ws_.async_read(buffer_, beast::bind_front_handler(&Session::on_read, shared_from_this()));
}

void Session::on_read(beast::error_code ec, std::size_t) {
    reading_ = false;
    // Closed by the peer, too big (Beast has already failed the connection
    // with 1009), timed out or aborted: the session ends here.
    if (ec) return;
    if (closing_) return;

    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    const Outcome outcome = ws_.got_binary() ? service_->handle_binary(state_) : service_->handle_text(state_, text);
    for (const auto& reply : outcome.replies) send(encode_reply(reply));
    if (outcome.close) {
        closing_ = true;
        close_after_queue_ = true;
        close_code_ = websocket::close_code::policy_error;
        if (queue_.empty()) close(close_code_);
        return;
    }
    if (queue_.size() < kMaxQueuedReplies) read();
}

void Session::send(std::string text) {
    queue_.push_back(std::move(text));
    if (queue_.size() == 1) write_next();
}

void Session::write_next() {
    ws_.text(true);
    ws_.async_write(net::buffer(queue_.front()), beast::bind_front_handler(&Session::on_write, shared_from_this()));
}

void Session::on_write(beast::error_code ec, std::size_t) {
    if (ec) return;
    queue_.pop_front();
    if (!queue_.empty()) {
        write_next();
        return;
    }
    if (close_after_queue_) {
        if (!close_started_) close(close_code_);
        return;
    }
    if (!reading_ && !closing_) read();
}

void Session::close(websocket::close_code code) {
    close_started_ = true;
    ws_.async_close(code, beast::bind_front_handler(&Session::on_close, shared_from_this()));
}

void Session::on_close(beast::error_code) {
    // The closing handshake is over (or failed); the stream is torn down and
    // the session ends with its last handler.
}

void Session::shutdown() {
    net::post(ws_.get_executor(), [self = shared_from_this()] { self->do_shutdown(); });
}

void Session::do_shutdown() {
    if (close_started_) return;
    if (!closing_) {
        close_after_queue_ = true;
        close_code_ = websocket::close_code::going_away;
    }
    closing_ = true;
    if (!websocket_) {
        // Still in the TLS handshake, the HTTP request or the upgrade: an
        // accept under way finishes and then closes (on_accept); anything
        // earlier is simply dropped.
        if (!request_.is_done()) beast::get_lowest_layer(ws_).close();
        return;
    }
    if (queue_.empty()) close(close_code_);
}

void Session::abort() {
    net::post(ws_.get_executor(), [self = shared_from_this()] {
        self->closing_ = true;
        beast::get_lowest_layer(self->ws_).close();
    });
}

}  // namespace umf::provider
