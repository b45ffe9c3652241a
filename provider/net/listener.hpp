// Accepts TCP connections and starts a DetectConnection for each, counted in
// the ConnectionRegistry so a shutdown can close them.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core/error.hpp>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "provider/net/connection_registry.hpp"
#include "provider/net/http_routes.hpp"
#include "provider/net/message_handler.hpp"

namespace umf::provider {

class ApiSessions;

class Listener : public std::enable_shared_from_this<Listener> {
public:
    // Binds and listens; throws boost::system::system_error.
    Listener(boost::asio::io_context& io, boost::asio::ssl::context& tls, const boost::asio::ip::tcp::endpoint& endpoint,
             std::shared_ptr<const MessageHandler> handler, std::shared_ptr<const HttpRoutes> routes,
             std::shared_ptr<ConnectionRegistry> registry, std::shared_ptr<ApiSessions> api_sessions,
             std::size_t max_connections = 1024);

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
    std::shared_ptr<const MessageHandler> handler_;
    std::shared_ptr<ConnectionRegistry> registry_;
    std::shared_ptr<ApiSessions> api_sessions_;
    std::shared_ptr<const HttpRoutes> routes_;  // one table for every connection
    std::size_t max_connections_;
    bool stopped_ = false;
};

}  // namespace umf::provider
