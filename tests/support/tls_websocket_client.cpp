#include "tests/support/tls_websocket_client.hpp"

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <chrono>
#include <functional>
#include <future>
#include <thread>

#include "shared/protocol/messages.hpp"
#include "tests/support/pinned_client.hpp"

namespace umf::test {

namespace net = boost::asio;
namespace ssl = boost::asio::ssl;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;

namespace {

constexpr auto kOperationTimeout = std::chrono::seconds(5);

// One completion handler type for every operation, so that each of Beast's
// operations is instantiated once.
struct Done {
    std::shared_ptr<std::promise<beast::error_code>> promise;
    void operator()(beast::error_code ec, std::size_t = 0) const { promise->set_value(ec); }
};

}  // namespace

struct TlsWebSocketClient::Connection {
    Connection(unsigned short port, const std::string& fingerprint)
        : port(port), tls(pinned_client_context(fingerprint)), ws(net::make_strand(io), tls), work(io.get_executor()) {
        ws.read_message_max(protocol::kMaxReplyBytes);
        thread = std::thread([this] { io.run(); });
    }
    ~Connection() {
        net::post(ws.get_executor(), [this] { beast::get_lowest_layer(ws).close(); });
        work.reset();
        thread.join();
    }

    // Starts the operation on the connection's strand and waits for it; on a
    // timeout the socket is closed, which ends the operation.
    beast::error_code run(const std::function<void(Done)>& start) {
        auto promise = std::make_shared<std::promise<beast::error_code>>();
        auto future = promise->get_future();
        net::post(ws.get_executor(), [&start, promise] { start(Done{promise}); });
        if (future.wait_for(kOperationTimeout) != std::future_status::ready) {
            ADD_FAILURE() << "operation timed out";
            net::post(ws.get_executor(), [this] { beast::get_lowest_layer(ws).close(); });
            future.wait();
        }
        return future.get();
    }

    beast::error_code connect_tls() {
        const net::ip::tcp::endpoint endpoint(net::ip::make_address("127.0.0.1"), port);
        if (auto ec = run([&](Done done) { beast::get_lowest_layer(ws).async_connect(endpoint, done); })) return ec;
        return run([&](Done done) { ws.next_layer().async_handshake(ssl::stream_base::client, done); });
    }

    unsigned short port;
    net::io_context io;
    ssl::context tls;
    websocket::stream<beast::ssl_stream<beast::tcp_stream>> ws;
    net::executor_work_guard<net::io_context::executor_type> work;
    std::thread thread;
};

TlsWebSocketClient::TlsWebSocketClient(unsigned short port, const std::string& fingerprint)
    : connection_(std::make_unique<Connection>(port, fingerprint)) {}

TlsWebSocketClient::~TlsWebSocketClient() = default;

beast::error_code TlsWebSocketClient::connect(const std::string& path) {
    Connection& c = *connection_;
    if (auto ec = c.connect_tls()) return ec;
    return c.run([&](Done done) { c.ws.async_handshake("127.0.0.1:" + std::to_string(c.port), path, done); });
}

beast::error_code TlsWebSocketClient::send(const std::string& text, bool binary) {
    Connection& c = *connection_;
    return c.run([&](Done done) {
        c.ws.binary(binary);
        c.ws.async_write(net::buffer(text), done);
    });
}

std::pair<beast::error_code, std::string> TlsWebSocketClient::read() {
    Connection& c = *connection_;
    beast::flat_buffer buffer;
    auto ec = c.run([&](Done done) { c.ws.async_read(buffer, done); });
    return {ec, beast::buffers_to_string(buffer.data())};
}

std::optional<websocket::close_code> TlsWebSocketClient::read_close() {
    for (int i = 0; i < 8; ++i) {
        auto [ec, text] = read();
        if (ec == websocket::error::closed) return static_cast<websocket::close_code>(connection_->ws.reason().code);
        if (ec) return std::nullopt;
    }
    return std::nullopt;
}

std::pair<beast::error_code, unsigned> TlsWebSocketClient::http_get(const std::string& target) {
    Connection& c = *connection_;
    if (auto ec = c.connect_tls()) return {ec, 0};
    http::request<http::empty_body> request(http::verb::get, target, 11);
    request.set(http::field::host, "127.0.0.1");
    if (auto ec = c.run([&](Done done) { http::async_write(c.ws.next_layer(), request, done); })) return {ec, 0};
    beast::flat_buffer buffer;
    http::response<http::string_body> response;
    auto ec = c.run([&](Done done) { http::async_read(c.ws.next_layer(), buffer, response, done); });
    return {ec, response.result_int()};
}

}  // namespace umf::test
