#include "server/detect_session.hpp"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/core/detect_ssl.hpp>
#include <chrono>
#include <string>

#include "server/http_session.hpp"
#include "server/listener.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace net = boost::asio;
namespace ssl = boost::asio::ssl;

namespace {

constexpr auto kHandshakeTimeout = std::chrono::seconds(30);

}  // namespace

DetectSession::DetectSession(net::ip::tcp::socket&& socket, ssl::context& tls, std::shared_ptr<const Service> service,
                             std::shared_ptr<SessionRegistry> registry, std::shared_ptr<HttpSessions> http_sessions,
                             std::shared_ptr<const HttpRoutes> routes)
    : executor_(socket.get_executor()),
      stream_(std::move(socket), tls),
      service_(std::move(service)),
      registry_(std::move(registry)),
      http_sessions_(std::move(http_sessions)),
      routes_(std::move(routes)),
      state_(std::make_unique<SessionState>()) {
    // Wrong pairing tokens are counted per address.
    beast::error_code ec;
    const auto remote = beast::get_lowest_layer(stream_).socket().remote_endpoint(ec);
    state_->peer = ec ? "unknown" : remote.address().to_string();
}

DetectSession::~DetectSession() {
    if (state_) service_->session_ended(*state_);
    if (registry_) registry_->remove(this);
}

void DetectSession::run() {
    registry_->add(this, weak_from_this());
    net::dispatch(executor_, [self = shared_from_this()] {
        if (self->closing_) return;
        beast::get_lowest_layer(self->stream_).expires_after(kHandshakeTimeout);
        // Someone typing http:// gets told to use https:// rather than a
        // connection that just drops.
        beast::async_detect_ssl(beast::get_lowest_layer(self->stream_), self->buffer_,
                                beast::bind_front_handler(&DetectSession::on_detect, self));
    });
}

void DetectSession::on_detect(beast::error_code ec, bool tls) {
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
                            beast::bind_front_handler(&DetectSession::on_handshake, shared_from_this()));
}

void DetectSession::on_handshake(beast::error_code ec, std::size_t used) {
    buffer_.consume(used);
    if (ec || closing_) return;
    auto http = std::make_shared<HttpSession>(std::move(stream_), std::move(buffer_), std::move(state_), service_,
                                              registry_, http_sessions_, routes_);
    registry_->hand_over(this, http.get(), http);
    next_ = http;
    http->run();
}

void DetectSession::shutdown() {
    net::post(executor_, [self = shared_from_this()] { self->stop(); });
}

void DetectSession::abort() {
    net::post(executor_, [self = shared_from_this()] {
        if (!self->state_) {
            if (auto next = self->next_.lock()) next->abort();
            return;
        }
        self->closing_ = true;
        beast::get_lowest_layer(self->stream_).close();
    });
}

void DetectSession::stop() {
    // Asked before the hand-over reached the strand: the HTTP session stops.
    if (!state_) {
        if (auto next = next_.lock()) next->shutdown();
        return;
    }
    closing_ = true;
    beast::get_lowest_layer(stream_).close();
}

}  // namespace umf::provider
