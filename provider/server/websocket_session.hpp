// A connection after its upgrade at /ws: the WebSocket session
// (docs/PROTOCOL.md, "Transport"). Each message is handed to the Service and
// its replies queued; at most one write is outstanding and the reading stops
// while kMaxQueuedReplies wait. Messages the service pushes later (a put's
// answer) come on any thread and join the queue on the strand.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <memory>
#include <string>

#include "common/tls_stream.hpp"
#include "server/connection.hpp"
#include "server/service.hpp"

namespace umf::provider {

class SessionRegistry;

class WebSocketSession : public Connection, public std::enable_shared_from_this<WebSocketSession> {
public:
    // The stream, the bytes read past the upgrade request and what the
    // connection established, from the HTTP session.
    WebSocketSession(TlsStream&& stream, boost::beast::flat_buffer&& buffer, std::unique_ptr<SessionState> state,
                     std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry);
    ~WebSocketSession() override;

    // Accepts the upgrade (on the strand).
    void run(const boost::beast::http::request<boost::beast::http::string_body>& upgrade);
    void shutdown() override;
    void abort() override;

private:
    void on_accept(boost::beast::error_code ec);
    // A message the service pushes to this session (on the strand).
    void push_message(std::string text);
    void read();
    void on_read(boost::beast::error_code ec, std::size_t);
    void send(std::string text);
    void write_next();
    void on_write(boost::beast::error_code ec, std::size_t);
    void close(boost::beast::websocket::close_code code);
    void on_close(boost::beast::error_code ec);
    void do_shutdown();

    boost::asio::any_io_executor executor_;
    boost::beast::websocket::stream<TlsStream> ws_;
    boost::beast::flat_buffer buffer_;
    std::unique_ptr<SessionState> state_;
    std::shared_ptr<const Service> service_;
    std::shared_ptr<SessionRegistry> registry_;
    std::deque<std::string> queue_;
    bool accepted_ = false;
    bool reading_ = false;
    bool closing_ = false;            // no more reading: a close is due or under way
    bool close_after_queue_ = false;  // close once the queue is sent
    bool close_started_ = false;
    boost::beast::websocket::close_code close_code_ = boost::beast::websocket::close_code::normal;
};

}  // namespace umf::provider
