// One session with a provider: TLS pinned to the pairing URL's fingerprint,
// the WebSocket on /ws, hello and welcome, then requests and their replies
// (docs/PROTOCOL.md, "Session"). Everything runs on the caller's thread: the
// frame loop calls poll() between frames, so replies are taken in without a
// second thread and without ever blocking on the network for long.
#pragma once

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <deque>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "requester/pinned_tls.hpp"
#include "shared/protocol/messages.hpp"
#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

class ProviderConnection {
public:
    ProviderConnection(protocol::PairingUrl url, NetTimeouts timeouts = {});
    ~ProviderConnection();
    ProviderConnection(const ProviderConnection&) = delete;
    ProviderConnection& operator=(const ProviderConnection&) = delete;

    // Connects, sends hello with the URL's token (and `device`, the name
    // the provider may remember "always accept from") and returns the
    // welcome. Throws GrabFailure: "connection", "certificate",
    // "unauthorized" (a wrong or revoked token), "protocol" or the code of
    // the provider's error.
    protocol::Welcome open(const std::string& client, const std::optional<std::string>& device = {});

    // Queues a message; it is written while the caller polls or waits.
    // Throws GrabFailure "connection" once the session has ended.
    void send(const protocol::Message& message);

    // Takes in what has arrived, without waiting, and returns the messages
    // received since the last call (replies to aims, errors). Throws
    // GrabFailure when the session has ended or the provider sent something
    // that is no message.
    std::vector<protocol::Message> poll();

    // Waits up to `timeout` for anything to arrive and returns it, as poll().
    std::vector<protocol::Message> wait_any(std::chrono::milliseconds timeout);

    // Waits up to timeouts.reply for the reply carrying `id`; other messages
    // received meanwhile are kept for poll(). Throws GrabFailure.
    protocol::Message wait_reply(const protocol::RequestId& id, const char* what);
    // The same with its own deadline: a put's later replies wait for a
    // person at the screen, longer than any reply of the provider itself.
    protocol::Message wait_reply(const protocol::RequestId& id, const char* what, std::chrono::milliseconds timeout);

    // A normal WebSocket close, waited for briefly. Never throws.
    void close();

    const protocol::PairingUrl& url() const { return url_; }

private:
    using Ws = boost::beast::websocket::stream<TlsStream>;

    void start_read();
    void write_next();
    // Throws the failure that ended the session, if any.
    void check_alive() const;

    protocol::PairingUrl url_;
    NetTimeouts timeouts_;
    boost::asio::io_context io_;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_;
    boost::asio::ssl::context tls_;
    std::unique_ptr<Ws> ws_;
    boost::beast::flat_buffer read_buffer_;
    std::deque<protocol::Message> inbox_;
    std::deque<std::string> outbox_;
    bool writing_ = false;
    bool open_ = false;
    bool reading_ = false;
    std::string failure_code_;     // set once the session has ended
    std::string failure_message_;
    int failure_exit_ = 0;
};

}  // namespace umf::requester
