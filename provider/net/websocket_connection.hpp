// A connection after its upgrade at /ws: one requester session over a
// WebSocket (docs/PROTOCOL.md, "Transport"). Each message is handed to the
// session's Conversation and its answer queued; at most one write is
// outstanding and the reading stops while kMaxQueuedReplies wait. Messages
// the conversation pushes later (a put's answer) come on any thread and join
// the queue on the strand.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <memory>
#include <string>

#include "provider/net/connection.hpp"
#include "provider/net/message_handler.hpp"
#include "provider/net/tls_stream.hpp"

namespace umf::provider {

class ConnectionRegistry;

class WebSocketConnection : public Connection, public std::enable_shared_from_this<WebSocketConnection> {
public:
    // The stream, the bytes read past the upgrade request and the remote
    // address, from the HTTP connection.
    WebSocketConnection(TlsStream&& stream, boost::beast::flat_buffer&& buffer, std::string peer,
                        std::shared_ptr<const MessageHandler> handler, std::shared_ptr<ConnectionRegistry> registry);
    ~WebSocketConnection() override;

    // Accepts the upgrade (on the strand).
    void run(const boost::beast::http::request<boost::beast::http::string_body>& upgrade);
    void shutdown() override;
    void abort() override;

private:
    void on_accept(boost::beast::error_code ec);
    // A message the conversation pushes (on the strand).
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
    std::string peer_;
    std::shared_ptr<const MessageHandler> handler_;
    std::unique_ptr<Conversation> conversation_;  // from run on; ends before handler_ goes
    std::shared_ptr<ConnectionRegistry> registry_;
    std::deque<std::string> queue_;
    bool accepted_ = false;
    bool reading_ = false;
    bool closing_ = false;            // no more reading: a close is due or under way
    bool close_after_queue_ = false;  // close once the queue is sent
    bool close_started_ = false;
    boost::beast::websocket::close_code close_code_ = boost::beast::websocket::close_code::normal;
};

}  // namespace umf::provider
