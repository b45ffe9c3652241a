// The start of a connection: its first bytes tell TLS from plain HTTP (which
// gets one fixed 400 telling to use https://), then the TLS handshake, all
// within 30 s; the TLS stream and the bytes read past the handshake go on to
// an HttpSession. What the connection establishes (SessionState) starts here
// and goes along with it.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <memory>

#include "common/tls_stream.hpp"
#include "server/connection.hpp"
#include "server/http_routes.hpp"
#include "server/http_sessions.hpp"
#include "server/service.hpp"

namespace umf::provider {

class SessionRegistry;

class DetectSession : public Connection, public std::enable_shared_from_this<DetectSession> {
public:
    DetectSession(boost::asio::ip::tcp::socket&& socket, boost::asio::ssl::context& tls,
                  std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry,
                  std::shared_ptr<HttpSessions> http_sessions, std::shared_ptr<const HttpRoutes> routes);
    ~DetectSession() override;

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
    std::shared_ptr<const Service> service_;
    std::shared_ptr<SessionRegistry> registry_;
    std::shared_ptr<HttpSessions> http_sessions_;
    std::shared_ptr<const HttpRoutes> routes_;
    std::unique_ptr<SessionState> state_;  // null once handed on
    std::weak_ptr<Connection> next_;       // the HTTP session it was handed to
    bool closing_ = false;
};

}  // namespace umf::provider
