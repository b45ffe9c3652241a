#include "server/listener.hpp"

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <chrono>

#include "server/detect_session.hpp"

namespace umf::provider {

namespace net = boost::asio;
namespace beast = boost::beast;
using tcp = net::ip::tcp;

void SessionRegistry::add(Connection* connection, std::weak_ptr<Connection> weak) {
    std::lock_guard lock(mutex_);
    sessions_[connection] = std::move(weak);
}

void SessionRegistry::hand_over(Connection* from, Connection* to, std::weak_ptr<Connection> weak) {
    std::lock_guard lock(mutex_);
    sessions_.erase(from);
    sessions_[to] = std::move(weak);
}

void SessionRegistry::remove(Connection* connection) {
    std::lock_guard lock(mutex_);
    ended_ += sessions_.erase(connection);
}

std::uint64_t SessionRegistry::ended() const {
    std::lock_guard lock(mutex_);
    return ended_;
}

std::vector<std::shared_ptr<Connection>> SessionRegistry::sessions() const {
    std::lock_guard lock(mutex_);
    std::vector<std::shared_ptr<Connection>> out;
    for (const auto& [ptr, weak] : sessions_)
        if (auto s = weak.lock()) out.push_back(std::move(s));
    return out;
}

std::size_t SessionRegistry::size() const {
    std::lock_guard lock(mutex_);
    return sessions_.size();
}

Listener::Listener(net::io_context& io, net::ssl::context& tls, const tcp::endpoint& endpoint,
                   std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry,
                   std::shared_ptr<HttpSessions> http_sessions, std::size_t max_connections)
    : io_(io),
      tls_(tls),
      strand_(net::make_strand(io)),
      acceptor_(strand_),
      service_(std::move(service)),
      registry_(std::move(registry)),
      http_sessions_(std::move(http_sessions)),
      routes_(make_http_routes(service_)),
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
        std::make_shared<DetectSession>(std::move(socket), tls_, service_, registry_, http_sessions_, routes_)->run();
    }
    accept();
}

}  // namespace umf::provider
