#include "provider/net/detect_connection.hpp"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/core/detect_ssl.hpp>
#include <chrono>
#include <string>

#include "provider/net/http_connection.hpp"
#include "provider/net/listener.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace net = boost::asio;
namespace ssl = boost::asio::ssl;

namespace {

constexpr auto kHandshakeTimeout = std::chrono::seconds(30);

}  // namespace

DetectConnection::DetectConnection(net::ip::tcp::socket&& socket, ssl::context& tls,
                                   std::shared_ptr<const MessageHandler> handler,
                             std::shared_ptr<ConnectionRegistry> registry, std::shared_ptr<ApiSessions> api_sessions,
                             std::shared_ptr<const HttpRoutes> routes)
    : executor_(socket.get_executor()),
      stream_(std::move(socket), tls),
      handler_(std::move(handler)),
      registry_(std::move(registry)),
      api_sessions_(std::move(api_sessions)),
      routes_(std::move(routes)) {
    beast::error_code ec;
    const auto remote = beast::get_lowest_layer(stream_).socket().remote_endpoint(ec);
    peer_ = ec ? "unknown" : remote.address().to_string();
}

DetectConnection::~DetectConnection() {
    if (registry_) registry_->remove(this);
}

void DetectConnection::run() {
    registry_->add(this, weak_from_this());
    net::dispatch(executor_, [self = shared_from_this()] {
        if (self->closing_) return;
        beast::get_lowest_layer(self->stream_).expires_after(kHandshakeTimeout);
        // Someone typing http:// gets told to use https:// rather than a
        // connection that just drops.
        beast::async_detect_ssl(beast::get_lowest_layer(self->stream_), self->buffer_,
                                beast::bind_front_handler(&DetectConnection::on_detect, self));
    });
}

void DetectConnection::on_detect(beast::error_code ec, bool tls) {
    if (ec || closing_) return;
    if (!tls) {
        static const std::string kPlainHttp =
            "HTTP/1.1 400 Bad Request\r\nServer: umf-provider\r\nContent-Type: text/plain; charset=utf-8\r\n"
            "Connection: close\r\nContent-Length: 60\r\n\r\n"
            "This is an HTTPS server: open the pairing link, https://...\n";
        net::async_write(beast::get_lowest_layer(stream_), net::buffer(kPlainHttp),
                         [self = shared_from_this()](beast::error_code, std::size_t) {
                             beast::error_code ignored;
                             beast::get_lowest_layer(self->stream_)
                                 .socket()
                                 .shutdown(net::ip::tcp::socket::shutdown_both, ignored);
                         });
        return;
    }
    // The handshake runs under the detection's timeout.
    stream_.async_handshake(ssl::stream_base::server, buffer_.data(),
                            beast::bind_front_handler(&DetectConnection::on_handshake, shared_from_this()));
}

void DetectConnection::on_handshake(beast::error_code ec, std::size_t used) {
    buffer_.consume(used);
    if (ec || closing_) return;
    handed_on_ = true;
    auto http = std::make_shared<HttpConnection>(std::move(stream_), std::move(buffer_), std::move(peer_), handler_,
                                              registry_, api_sessions_, routes_);
    registry_->hand_over(this, http.get(), http);
    next_ = http;
    http->run();
}

void DetectConnection::shutdown() {
    net::post(executor_, [self = shared_from_this()] { self->stop(); });
}

void DetectConnection::abort() {
    net::post(executor_, [self = shared_from_this()] {
        if (self->handed_on_) {
            if (auto next = self->next_.lock()) next->abort();
            return;
        }
        self->closing_ = true;
        beast::get_lowest_layer(self->stream_).close();
    });
}

void DetectConnection::stop() {
    // Asked before the hand-over reached the strand: the HTTP session stops.
    if (handed_on_) {
        if (auto next = next_.lock()) next->shutdown();
        return;
    }
    closing_ = true;
    beast::get_lowest_layer(stream_).close();
}

}  // namespace umf::provider
