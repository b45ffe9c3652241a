// A connection's HTTP requests once TLS is up, kept alive between requests
// until one upgrades to a WebSocketConnection at /ws, which takes the stream on.
// A request's header is read first (at most 8 KiB, its framing checked);
// a route that takes it then (an upload) reads the body itself, anything
// else is read whole (a body of at most 16 KiB) and goes to its route
// (http_routes.hpp), which answers through the HttpExchange this connection
// lends it. The HTTPS transport (/api/, http_connection_api.cpp) is the
// connection's own: a long poll waits on a timer of the strand while a read
// watches for the client leaving. All of a connection's work runs on its strand,
// one write at a time; an error answer that ends the connection lingers for
// what the peer still sends.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <memory>
#include <optional>
#include <string>

#include "provider/net/api_sessions.hpp"
#include "provider/net/connection.hpp"
#include "provider/net/http_exchange.hpp"
#include "provider/net/http_routes.hpp"
#include "provider/net/message_handler.hpp"
#include "provider/net/tls_stream.hpp"

namespace umf::provider {

class ConnectionRegistry;

// A request's time to arrive (also a kept-alive connection's idle timeout),
// and an answer's to be written.
inline constexpr auto kHttpTimeout = std::chrono::seconds(30);
inline constexpr std::size_t kMaxRequestHeaderBytes = 8 * 1024;
// A body read whole: one message of the HTTPS transport (docs/PROTOCOL.md, "Limits").
inline constexpr std::size_t kMaxRequestBodyBytes = 16 * 1024;

class HttpConnection : public Connection, public HttpExchange, public std::enable_shared_from_this<HttpConnection> {
public:
    // The stream, the bytes read past the TLS handshake and what the
    // connection established, from the DetectConnection.
    HttpConnection(TlsStream&& stream, boost::beast::flat_buffer&& buffer, std::string peer,
                   std::shared_ptr<const MessageHandler> handler, std::shared_ptr<ConnectionRegistry> registry,
                   std::shared_ptr<ApiSessions> api_sessions, std::shared_ptr<const HttpRoutes> routes);
    ~HttpConnection() override;

    // Reads the first request (on the strand).
    void run();
    void shutdown() override;
    void abort() override;

    // HttpExchange, for the routes.
    TlsStream& stream() override { return stream_; }
    boost::beast::flat_buffer& buffer() override { return buffer_; }
    std::shared_ptr<HttpExchange> hold() override { return shared_from_this(); }
    bool stopping() const override { return closing_; }
    void restart_timeout() override;
    void answer_json(int status, bool keep_alive, std::string body) override;
    void answer_error(boost::beast::http::status status, bool keep_alive, const protocol::Error& error,
                      const char* allow = nullptr) override;
    using HttpExchange::answer_error;
    void written(bool keep_alive) override { after_response(keep_alive); }
    void drop() override;

private:
    void read_request();
    void on_header(boost::beast::error_code ec, std::size_t);
    void request_failed(boost::beast::error_code ec);
    void on_request(boost::beast::error_code ec, std::size_t);
    // The upgrade: the stream, the buffer and the peer go on to a
    // WebSocketConnection, and the registry's entry with them.
    void upgrade(const HttpRequest& req);
    // The HTTPS transport's calls under /api/ (http_connection_api.cpp).
    void serve_api(const HttpRequest& req);
    void api_response(int status, bool keep_alive, std::string body, const char* allow = nullptr);
    template <class Body>
    void write_response(std::shared_ptr<boost::beast::http::response<Body>> response);
    void after_response(bool keep_alive);
    void end_tls();
    void do_shutdown();

    // The long poll (http_connection_api.cpp).
    void start_poll(std::string_view id, bool keep_alive);
    void on_poll_timer(boost::beast::error_code ec, std::uint64_t serial);
    void finish_poll(std::uint64_t poll, ApiSessions::Reply reply);
    void watch();
    void on_watch(boost::beast::error_code ec, std::size_t bytes);
    void arm_timer(std::chrono::milliseconds after,
                   void (HttpConnection::*handler)(boost::beast::error_code, std::uint64_t));
    void on_idle_timer(boost::beast::error_code ec, std::uint64_t serial);

    boost::asio::any_io_executor executor_;  // the connection's strand, also once the stream is handed on
    TlsStream stream_;
    std::shared_ptr<const MessageHandler> handler_;
    std::shared_ptr<ConnectionRegistry> registry_;
    std::shared_ptr<ApiSessions> api_sessions_;
    std::shared_ptr<const HttpRoutes> routes_;
    boost::beast::flat_buffer buffer_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::empty_body>> header_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> request_;
    std::shared_ptr<void> response_;       // the connection's own response being written
    std::string peer_;                     // the remote address
    bool handed_on_ = false;               // upgraded: the WebSocket has the stream
    std::weak_ptr<Connection> next_;       // the WebSocket connection it was handed to
    bool closing_ = false;                 // the server is stopping

    // The long poll (GET /api/session/ID/events) and the read that watches
    // for the client leaving meanwhile; that read becomes the start of the
    // next request once the poll is answered.
    boost::asio::steady_timer timer_;  // the poll's timeout, then the idle timeout after it
    std::uint64_t timer_serial_ = 0;   // a handler of an older arming does nothing
    std::uint64_t poll_serial_ = 0;    // this connection's polls
    std::uint64_t poll_ticket_ = 0;    // ApiSessions' ticket for the open one
    bool poll_pending_ = false;
    bool poll_keep_alive_ = false;
    bool watching_ = false;
    bool resume_after_watch_ = false;  // answered: the watch read leads into the next request

    bool linger_after_response_ = false;  // an error answer that ends the connection
};

}  // namespace umf::provider
