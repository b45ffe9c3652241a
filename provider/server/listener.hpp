// Accepts TCP connections and starts a Session for each; keeps track of the
// live sessions so a shutdown can close them.
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

#include "server/service.hpp"

namespace umf::provider {

class HttpSessions;
class Session;

// The live sessions, by address. Sessions add themselves when they start and
// remove themselves when destroyed.
class SessionRegistry {
public:
    void add(Session* session, std::weak_ptr<Session> weak);
    void remove(Session* session);
    // The sessions still alive.
    std::vector<std::shared_ptr<Session>> sessions() const;
    std::size_t size() const;
    // Connections ended since the registry was made (the heap trimmer's cue).
    std::uint64_t ended() const;

private:
    mutable std::mutex mutex_;
    std::unordered_map<Session*, std::weak_ptr<Session>> sessions_;
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
    std::size_t max_connections_;
    bool stopped_ = false;
};

}  // namespace umf::provider
