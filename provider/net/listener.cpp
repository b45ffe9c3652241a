#include "provider/net/listener.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <chrono>

#include "provider/net/detect_connection.hpp"

namespace umf::provider {

namespace net = boost::asio;
namespace beast = boost::beast;
using tcp = net::ip::tcp;

Listener::Listener(net::io_context& io, net::ssl::context& tls, const tcp::endpoint& endpoint,
                   std::shared_ptr<const MessageHandler> handler, std::shared_ptr<const HttpRoutes> routes,
                   std::shared_ptr<ConnectionRegistry> registry, std::shared_ptr<ApiSessions> api_sessions,
                   std::size_t max_connections)
    : io_(io),
      tls_(tls),
      strand_(net::make_strand(io)),
      acceptor_(strand_),
      handler_(std::move(handler)),
      registry_(std::move(registry)),
      api_sessions_(std::move(api_sessions)),
      routes_(std::move(routes)),
      max_connections_(max_connections) {
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(net::socket_base::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen(net::socket_base::max_listen_connections);
    endpoint_ = acceptor_.local_endpoint();
}

void Listener::run() {
    net::post(strand_, [self = shared_from_this()] { self->accept(); });
}

void Listener::stop() {
    net::post(strand_, [self = shared_from_this()] {
        self->stopped_ = true;
        beast::error_code ignored;
        self->acceptor_.close(ignored);
    });
}

void Listener::accept() {
    if (stopped_) return;
    // Each connection gets its own strand.
    acceptor_.async_accept(net::make_strand(io_), beast::bind_front_handler(&Listener::on_accept, shared_from_this()));
}

void Listener::on_accept(beast::error_code ec, tcp::socket socket) {
    if (stopped_ || ec == net::error::operation_aborted) return;
    if (ec) {
        // Out of descriptors and the like: try again shortly rather than spin.
        auto timer = std::make_shared<net::steady_timer>(strand_, std::chrono::milliseconds(100));
        timer->async_wait([self = shared_from_this(), timer](beast::error_code) { self->accept(); });
        return;
    }
    if (registry_->size() >= max_connections_) {
        // Full: the connection is dropped before any TLS work is spent on it.
        beast::error_code ignored;
        socket.close(ignored);
    } else {
        std::make_shared<DetectConnection>(std::move(socket), tls_, handler_, registry_, api_sessions_, routes_)->run();
    }
    accept();
}

}  // namespace umf::provider
