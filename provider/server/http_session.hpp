// A connection's HTTP requests once TLS is up (one-time downloads under /dl/,
// uploads of accepted puts under /up/, the web client's files, the HTTPS
// transport under /api/ handed to HttpSessions), kept alive between requests
// until one upgrades to a WebSocketSession at /ws, which takes the stream on.
// A request's header is read first: an upload's body then streams to a file
// in chunks, any other body is read whole (at most 16 KiB). All of a
// session's work runs on its strand, one write at a time. A long poll waits
// on a timer of the strand while a read watches for the client leaving.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/tls_stream.hpp"
#include "put/upload_sink.hpp"
#include "put/upload_table.hpp"
#include "server/connection.hpp"
#include "server/http_sessions.hpp"
#include "server/service.hpp"

namespace umf::provider {

class SessionRegistry;

// The WebSocket path (docs/PROTOCOL.md, "Transport").
inline constexpr const char* kWebSocketPath = "/ws";
// The HTTPS transport's paths start so (docs/PROTOCOL.md, "HTTPS transport").
inline constexpr const char* kApiPrefix = "/api/";

class HttpSession : public Connection, public std::enable_shared_from_this<HttpSession> {
public:
    // The stream, the bytes read past the TLS handshake and what the
    // connection established, from the DetectSession.
    HttpSession(TlsStream&& stream, boost::beast::flat_buffer&& buffer, std::unique_ptr<SessionState> state,
                std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry,
                std::shared_ptr<HttpSessions> http_sessions);
    ~HttpSession() override;

    // Reads the first request (on the strand).
    void run();
    void shutdown() override;
    void abort() override;

private:
    void read_request();
    void on_header(boost::beast::error_code ec, std::size_t);
    void request_failed(boost::beast::error_code ec);
    void on_request(boost::beast::error_code ec, std::size_t);
    // PUT /up/<token> (docs/PROTOCOL.md, "Upload").
    void start_upload();
    void read_upload();
    void on_upload(boost::beast::error_code ec, std::size_t);
    void finish_upload();
    // The upload failed: its file removed, the put's session told; answered
    // with `status` while the connection is there (`answer`), else closed.
    void fail_upload(protocol::ErrorCode code, const std::string& message, bool answer);
    void serve_http(const boost::beast::http::request<boost::beast::http::string_body>& req);
    void serve_download(const boost::beast::http::request<boost::beast::http::string_body>& req);
    void serve_api(const boost::beast::http::request<boost::beast::http::string_body>& req);
    void api_response(int status, bool keep_alive, std::string body, const char* allow = nullptr);
    // Every error answer over HTTP: its status and the one error body
    // (protocol/http_error_body.hpp); without keep_alive the connection
    // closes once it is written.
    void answer_error(boost::beast::http::status status, bool keep_alive, const protocol::Error& error,
                      const char* allow = nullptr);
    void answer_error(boost::beast::http::status status, bool keep_alive, protocol::ErrorCode code,
                      const std::string& message, const char* allow = nullptr);
    void start_poll(std::string_view id, bool keep_alive);
    void on_poll_timer(boost::beast::error_code ec, std::uint64_t serial);
    void finish_poll(std::uint64_t poll, HttpSessions::Reply reply);
    void watch();
    void on_watch(boost::beast::error_code ec, std::size_t bytes);
    void arm_timer(std::chrono::milliseconds after,
                   void (HttpSession::*handler)(boost::beast::error_code, std::uint64_t));
    void on_idle_timer(boost::beast::error_code ec, std::uint64_t serial);
    template <class Body>
    void write_response(std::shared_ptr<boost::beast::http::response<Body>> response);
    void after_response(bool keep_alive);
    void end_tls();
    // The upgrade: the stream, the buffer and the state go on to a
    // WebSocketSession, and the registry's entry with them.
    void upgrade(const boost::beast::http::request<boost::beast::http::string_body>& req);
    void do_shutdown();

    boost::asio::any_io_executor executor_;  // the connection's strand, also once the stream is handed on
    TlsStream stream_;
    std::shared_ptr<const Service> service_;
    std::shared_ptr<SessionRegistry> registry_;
    std::shared_ptr<HttpSessions> http_sessions_;
    boost::beast::flat_buffer buffer_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::empty_body>> header_;
    std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> request_;
    // An upload under way: its parser (the body in chunks), the accepted put
    // and the file the bytes go to.
    std::optional<boost::beast::http::request_parser<boost::beast::http::buffer_body>> upload_;
    std::optional<UploadEntry> upload_entry_;
    std::unique_ptr<UploadSink> upload_sink_;
    std::vector<char> upload_chunk_;
    std::shared_ptr<void> response_;  // the response being written
    std::unique_ptr<SessionState> state_;  // null once handed on
    std::weak_ptr<Connection> next_;       // the WebSocket session it was handed to
    bool closing_ = false;                 // the server is stopping

    // The long poll (GET /api/session/ID/events) and the read that watches
    // for the client leaving meanwhile; that read becomes the start of the
    // next request once the poll is answered.
    boost::asio::steady_timer timer_;  // the poll's timeout, then the idle timeout after it
    std::uint64_t timer_serial_ = 0;   // a handler of an older arming does nothing
    std::uint64_t poll_serial_ = 0;    // this connection's polls
    std::uint64_t poll_ticket_ = 0;    // HttpSessions' ticket for the open one
    bool poll_pending_ = false;
    bool poll_keep_alive_ = false;
    bool watching_ = false;
    bool resume_after_watch_ = false;  // answered: the watch read leads into the next request

    bool linger_after_response_ = false;  // an error answer that ends the connection
};

}  // namespace umf::provider
