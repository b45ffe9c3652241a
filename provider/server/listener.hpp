// Accepts TCP connections and starts a DetectSession for each; keeps track of
// the live connections so a shutdown can close them.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core/error.hpp>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>

#include "server/connection.hpp"
#include "server/http_routes.hpp"
#include "server/service.hpp"

namespace umf::provider {

class HttpSessions;

// The live connections, by address. A connection adds itself when it starts,
// hands its entry on when it changes role (detection to HTTP to WebSocket)
// and removes it when its last role is destroyed: one entry and one end per
// connection.
class SessionRegistry {
public:
    void add(Connection* connection, std::weak_ptr<Connection> weak);
    // `from`'s entry is now `to`'s; no connection ended.
    void hand_over(Connection* from, Connection* to, std::weak_ptr<Connection> weak);
    // Nothing when `connection` handed its entry on.
    void remove(Connection* connection);
    // The connections still alive.
    std::vector<std::shared_ptr<Connection>> sessions() const;
    std::size_t size() const;
    // Connections ended since the registry was made (the heap trimmer's cue).
    std::uint64_t ended() const;

private:
    mutable std::mutex mutex_;
    std::unordered_map<Connection*, std::weak_ptr<Connection>> sessions_;
    std::uint64_t ended_ = 0;
};

class Listener : public std::enable_shared_from_this<Listener> {
public:
    // Binds and listens; throws boost::system::system_error.
    Listener(boost::asio::io_context& io, boost::asio::ssl::context& tls, const boost::asio::ip::tcp::endpoint& endpoint,
             std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry,
             std::shared_ptr<HttpSessions> http_sessions, std::size_t max_connections = 1024);

    void run();
    // From any thread: stops accepting.
    void stop();
    boost::asio::ip::tcp::endpoint local_endpoint() const { return endpoint_; }

private:
    void accept();
    void on_accept(boost::beast::error_code ec, boost::asio::ip::tcp::socket socket);

    boost::asio::io_context& io_;
    boost::asio::ssl::context& tls_;
    boost::asio::strand<boost::asio::io_context::executor_type> strand_;
    boost::asio::ip::tcp::acceptor acceptor_;
    boost::asio::ip::tcp::endpoint endpoint_;
    std::shared_ptr<const Service> service_;
    std::shared_ptr<SessionRegistry> registry_;
    std::shared_ptr<HttpSessions> http_sessions_;
    std::shared_ptr<const HttpRoutes> routes_;  // one table for every connection
    std::size_t max_connections_;
    bool stopped_ = false;
};

}  // namespace umf::provider
