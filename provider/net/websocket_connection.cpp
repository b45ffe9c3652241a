#include "provider/net/websocket_connection.hpp"

#include <boost/asio/post.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <chrono>

#include "provider/net/lingering_close.hpp"
#include "provider/net/listener.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;

namespace {

// Replies waiting beyond this stop the reading until the peer takes them.
constexpr std::size_t kMaxQueuedReplies = 64;

}  // namespace

WebSocketConnection::WebSocketConnection(TlsStream&& stream, beast::flat_buffer&& buffer, std::string peer,
                                         std::shared_ptr<const MessageHandler> handler,
                                         std::shared_ptr<ConnectionRegistry> registry)
    : executor_(stream.get_executor()),
      ws_(std::move(stream)),
      buffer_(std::move(buffer)),
      peer_(std::move(peer)),
      handler_(std::move(handler)),
      registry_(std::move(registry)) {}

WebSocketConnection::~WebSocketConnection() {
    conversation_.reset();  // the session ends before the connection leaves the registry
    if (registry_) registry_->remove(this);
}

void WebSocketConnection::run(const http::request<http::string_body>& upgrade) {
    // What the conversation pushes (a put's answer) comes on any thread and
    // is sent from the strand.
    conversation_ = handler_->open(peer_, [weak = weak_from_this(), executor = executor_](std::string message) {
        net::post(executor, [weak, message = std::move(message)]() mutable {
            if (auto self = weak.lock()) self->push_message(std::move(message));
        });
    });
    beast::get_lowest_layer(ws_).expires_never();
    // A requester that vanished (a phone locked, Wi-Fi gone) is pinged after
    // 30 s of silence and dropped after 60.
    auto timeouts = websocket::stream_base::timeout::suggested(beast::role_type::server);
    timeouts.idle_timeout = std::chrono::seconds(60);
    timeouts.keep_alive_pings = true;
    ws_.set_option(timeouts);
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::server, "umf-provider"); }));
    ws_.read_message_max(handler_->max_message_bytes());
    ws_.async_accept(upgrade, beast::bind_front_handler(&WebSocketConnection::on_accept, shared_from_this()));
}

void WebSocketConnection::on_accept(beast::error_code ec) {
    if (ec) return;
    accepted_ = true;
    // The upgrade request is read: an idle session keeps no more buffer than
    // its next message needs (memory per idle requester, docs/BENCHMARKS.md).
    buffer_.shrink_to_fit();
    if (closing_) {
        if (!close_started_) close(close_code_);
        return;
    }
    read();
}

void WebSocketConnection::push_message(std::string text) {
    if (!accepted_ || closing_) return;
    send(std::move(text));
}

void WebSocketConnection::read() {
    reading_ = true;
    ws_.async_read(buffer_, beast::bind_front_handler(&WebSocketConnection::on_read, shared_from_this()));
}

void WebSocketConnection::on_read(beast::error_code ec, std::size_t) {
    reading_ = false;
    // The session ends here: closed by the peer, timed out, aborted, or
    // failed by Beast, which has sent its close (1009 for a message too
    // big, 1007 for text that is not UTF-8). The peer may still be sending
    // the rest of what failed it: closing under that would reset the
    // connection and could destroy the close before the peer reads it.
    if (ec) {
        if (!closing_ && ec != net::error::operation_aborted)
            lingering_close(beast::get_lowest_layer(ws_), shared_from_this());
        return;
    }
    if (closing_) return;

    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    if (buffer_.capacity() > 4096) buffer_.shrink_to_fit();  // after a rare large message
    Answer answer = ws_.got_binary() ? conversation_->binary() : conversation_->text(text);
    for (auto& message : answer.messages) send(std::move(message));
    if (answer.then != Answer::Then::go_on) {
        closing_ = true;
        close_after_queue_ = true;
        close_code_ = answer.then == Answer::Then::restart ? websocket::close_code::service_restart
                                                           : websocket::close_code::policy_error;
        if (queue_.empty()) close(close_code_);
        return;
    }
    if (queue_.size() < kMaxQueuedReplies) read();
}

void WebSocketConnection::send(std::string text) {
    queue_.push_back(std::move(text));
    if (queue_.size() == 1) write_next();
}

void WebSocketConnection::write_next() {
    ws_.text(true);
    ws_.async_write(net::buffer(queue_.front()),
                    beast::bind_front_handler(&WebSocketConnection::on_write, shared_from_this()));
}

void WebSocketConnection::on_write(beast::error_code ec, std::size_t) {
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

void WebSocketConnection::close(websocket::close_code code) {
    close_started_ = true;
    ws_.async_close(code, beast::bind_front_handler(&WebSocketConnection::on_close, shared_from_this()));
}

void WebSocketConnection::on_close(beast::error_code) {
    // The closing handshake is over (or failed); the stream is torn down and
    // the session ends with its last handler.
}

void WebSocketConnection::shutdown() {
    net::post(executor_, [self = shared_from_this()] { self->do_shutdown(); });
}

void WebSocketConnection::do_shutdown() {
    if (close_started_) return;
    if (!closing_) {
        close_after_queue_ = true;
        close_code_ = websocket::close_code::going_away;
    }
    closing_ = true;
    // An accept under way finishes and then closes (on_accept).
    if (!accepted_) return;
    if (queue_.empty()) close(close_code_);
}

void WebSocketConnection::abort() {
    net::post(executor_, [self = shared_from_this()] {
        self->closing_ = true;
        beast::get_lowest_layer(self->ws_).close();
    });
}

}  // namespace umf::provider
