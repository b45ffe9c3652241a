// The start of a connection: its first bytes tell TLS from plain HTTP (which
// gets one fixed 400 telling to use https://), then the TLS handshake, all
// within 30 s; the TLS stream and the bytes read past the handshake go on to
// an HttpConnection, with the remote address.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <memory>

#include "provider/net/api_sessions.hpp"
#include "provider/net/connection.hpp"
#include "provider/net/http_routes.hpp"
#include "provider/net/message_handler.hpp"
#include "provider/net/tls_stream.hpp"

namespace umf::provider {

class ConnectionRegistry;

class DetectConnection : public Connection, public std::enable_shared_from_this<DetectConnection> {
public:
    DetectConnection(boost::asio::ip::tcp::socket&& socket, boost::asio::ssl::context& tls,
                     std::shared_ptr<const MessageHandler> handler, std::shared_ptr<ConnectionRegistry> registry,
                  std::shared_ptr<ApiSessions> api_sessions, std::shared_ptr<const HttpRoutes> routes);
    ~DetectConnection() override;

    void run();
    void shutdown() override;
    void abort() override;

private:
    void on_detect(boost::beast::error_code ec, bool tls);
    void on_handshake(boost::beast::error_code ec, std::size_t used);
    // On the strand: dropped, or the stop passed on to the HTTP session.
    void stop();

    boost::asio::any_io_executor executor_;  // the connection's strand, also once the stream is handed on
    TlsStream stream_;
    boost::beast::flat_buffer buffer_;
    std::shared_ptr<const MessageHandler> handler_;
    std::shared_ptr<ConnectionRegistry> registry_;
    std::shared_ptr<ApiSessions> api_sessions_;
    std::shared_ptr<const HttpRoutes> routes_;
    std::string peer_;                // the remote address: wrong pairing tokens are counted per address
    bool handed_on_ = false;          // the HTTP connection has the stream
    std::weak_ptr<Connection> next_;  // the HTTP connection it was handed to
    bool closing_ = false;
};

}  // namespace umf::provider
