#include "provider/net/server.hpp"

#include <boost/asio/ip/address.hpp>
#include <boost/asio/strand.hpp>
#include <stdexcept>

#include "provider/net/heap_trim.hpp"
#include "provider/net/listener.hpp"

namespace umf::provider {

namespace net = boost::asio;

Server::Server(std::shared_ptr<const MessageHandler> handler, std::shared_ptr<const HttpRoutes> routes,
               const TlsIdentity& identity, ServerOptions options)
    : handler_(std::move(handler)),
      routes_(std::move(routes)),
      options_(std::move(options)),
      io_(options_.threads > 0 ? options_.threads : 1),
      identity_(identity),
      tls_(net::ssl::context::tls_server),
      registry_(std::make_shared<ConnectionRegistry>()),
      api_sessions_(ApiSessions::create(net::make_strand(io_), handler_, options_.api_sessions)) {
    configure_server_context(tls_, identity_);
}

Server::~Server() { stop(); }

void Server::start() {
    if (running_) return;
    boost::system::error_code ec;
    const auto address = net::ip::make_address(options_.bind_address, ec);
    if (ec) throw std::runtime_error("not an IP address: " + options_.bind_address);
    const net::ip::tcp::endpoint endpoint(address, options_.port);
    try {
        listener_ = std::make_shared<Listener>(io_, tls_, endpoint, handler_, routes_, registry_, api_sessions_,
                                               options_.max_connections);
    } catch (const boost::system::system_error& e) {
        throw std::runtime_error("cannot listen on " + options_.bind_address + " port " +
                                 std::to_string(options_.port) + ": " + e.code().message());
    }
    port_ = listener_->local_endpoint().port();
    listener_->run();
    trimmer_ = std::make_shared<HeapTrimmer>(io_, registry_);
    trimmer_->start();
    running_ = true;
    const int n = options_.threads > 0 ? options_.threads : 1;
    for (int i = 0; i < n; ++i) threads_.emplace_back([this] { io_.run(); });
}

std::size_t Server::connection_count() const { return registry_->size(); }

void Server::stop(std::chrono::milliseconds grace) {
    if (!running_) return;
    running_ = false;
    listener_->stop();
    trimmer_->stop();
    // Open polls are answered with "closed": 1001 and the HTTP sessions end.
    api_sessions_->stop();
    for (const auto& connection : registry_->connections()) connection->shutdown();

    // The io_context runs out of work once the listener and every connection
    // are done; what is still open after the grace period is dropped.
    const auto wait_for_connections = [this](std::chrono::milliseconds limit) {
        const auto deadline = std::chrono::steady_clock::now() + limit;
        while (registry_->size() > 0 && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        return registry_->size() == 0;
    };
    if (!wait_for_connections(grace)) {
        for (const auto& connection : registry_->connections()) connection->abort();
        if (!wait_for_connections(std::chrono::milliseconds(1000))) io_.stop();
    }
    for (auto& t : threads_) t.join();
    threads_.clear();
    listener_.reset();
}

}  // namespace umf::provider
