// A requester's TLS WebSocket to a provider on this machine, pinned to the
// provider's certificate as requesters are (tests/support/pinned_client.hpp):
// for the server tests. It runs its own io_context thread; every operation is
// started there and waited for with a timeout (a failure of the test when it
// runs out). Compiled once, behind this plain interface: Beast's TLS and
// WebSocket operations are the dearest templates the tests instantiate.
#pragma once

#include <boost/beast/core/error.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace umf::test {

class TlsWebSocketClient {
public:
    TlsWebSocketClient(unsigned short port, const std::string& fingerprint);
    ~TlsWebSocketClient();
    TlsWebSocketClient(const TlsWebSocketClient&) = delete;
    TlsWebSocketClient& operator=(const TlsWebSocketClient&) = delete;

    // TCP to 127.0.0.1, TLS with the pinned certificate, then the WebSocket
    // handshake at path.
    boost::beast::error_code connect(const std::string& path = "/ws");
    boost::beast::error_code send(const std::string& text, bool binary = false);
    // The next message, or the error that ended the session.
    std::pair<boost::beast::error_code, std::string> read();
    // Reads until the session ends: the close code the provider sent, none
    // when it ended otherwise or went on past a few messages.
    std::optional<boost::beast::websocket::close_code> read_close();
    // Plain HTTP over a new TLS connection, for the paths that are not the
    // WebSocket: the error and the answer's status.
    std::pair<boost::beast::error_code, unsigned> http_get(const std::string& target);

private:
    struct Connection;
    std::unique_ptr<Connection> connection_;
};

}  // namespace umf::test
