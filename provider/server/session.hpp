// One connection: the TLS handshake, then HTTP requests (one-time downloads
// under /dl/, uploads of accepted puts under /up/, the web client's files,
// the HTTPS transport under /api/ handed to HttpSessions, kept alive between
// requests) until one upgrades to the WebSocket session at /ws. A request's
// header is read first: an upload's body then streams to a file in chunks,
// any other body is read whole (at most 16 KiB). All of a session's work runs on its strand; at
// most one write is outstanding and replies wait in a queue. A long poll
// waits on a timer of the strand while a read watches for the client leaving.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "put/upload_sink.hpp"
#include "put/upload_table.hpp"
#include "server/http_sessions.hpp"
#include "server/service.hpp"

namespace umf::provider {

class SessionRegistry;

// The WebSocket path (docs/PROTOCOL.md, "Transport").
inline constexpr const char* kWebSocketPath = "/ws";
// The HTTPS transport's paths start so (docs/PROTOCOL.md, "HTTPS transport").
inline constexpr const char* kApiPrefix = "/api/";

class Session : public std::enable_shared_from_this<Session> {
public:
    Session(boost::asio::ip::tcp::socket&& socket, boost::asio::ssl::context& tls,
            std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry,
            std::shared_ptr<HttpSessions> http_sessions);
    ~Session();

    void run();
    // From any thread: a WebSocket session closes with going_away (1001);
    // a connection still in its handshake is dropped.
    void shutdown();
    // From any thread: drops the connection at once.
    void abort();

private:
    using TlsStream = boost::beast::ssl_stream<boost::beast::tcp_stream>;

    void on_detect(boost::beast::error_code ec, bool tls);
    void on_tls_handshake(boost::beast::error_code ec);
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
    // A message the service pushes to this WebSocket session (on the strand).
    void push_message(std::string text);
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
    void arm_timer(std::chrono::milliseconds after, void (Session::*handler)(boost::beast::error_code, std::uint64_t));
    void on_idle_timer(boost::beast::error_code ec, std::uint64_t serial);
    template <class Body>
    void write_response(std::shared_ptr<boost::beast::http::response<Body>> response);
    void after_response(bool keep_alive);
    void end_tls();
    // After an error answer (or a 1009 close): FIN, then the peer's bytes
    // read and dropped until it closes, kLingerTime or kMaxLingerBytes.
    void lingering_close();
    void drain();
    void on_accept(boost::beast::error_code ec);
    void read();
    void on_read(boost::beast::error_code ec, std::size_t);
    void send(std::string text);
    void write_next();
    void on_write(boost::beast::error_code ec, std::size_t);
    void close(boost::beast::websocket::close_code code);
    void on_close(boost::beast::error_code ec);
    void do_shutdown();

    boost::beast::websocket::stream<TlsStream> ws_;
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
    SessionState state_;
    std::deque<std::string> queue_;
    bool websocket_ = false;  // accepted
    bool reading_ = false;
    bool closing_ = false;            // no more reading: a close is due or under way
    bool close_after_queue_ = false;  // close once the queue is sent
    bool close_started_ = false;
    boost::beast::websocket::close_code close_code_ = boost::beast::websocket::close_code::normal;

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
    std::unique_ptr<std::array<char, 16 * 1024>> linger_buffer_;
    std::size_t linger_bytes_ = 0;
};

}  // namespace umf::provider
