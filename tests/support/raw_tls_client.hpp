// Bytes over TLS exactly as written, and everything the other side sends
// until it closes: for requests no well-behaved client would send (ambiguous
// framing, a second request hidden in a body). No certificate check: the
// tests that use it are about what the provider answers, not who it is.
#pragma once

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/ssl.hpp>
#include <chrono>
#include <string>

namespace umf::test {

// Everything received until the provider closed the connection or
// `patience` passed without a byte; `closed` says which.
struct RawExchange {
    std::string received;
    bool closed = false;
    std::string write_error;  // empty when every byte was written
};

inline RawExchange raw_tls_exchange(unsigned short port, const std::string& bytes,
                                    std::chrono::milliseconds patience = std::chrono::seconds(5)) {
    namespace net = boost::asio;
    namespace beast = boost::beast;
    net::io_context io;
    net::ssl::context ctx(net::ssl::context::tls_client);
    ctx.set_verify_mode(net::ssl::verify_none);
    beast::ssl_stream<beast::tcp_stream> stream(io, ctx);
    beast::get_lowest_layer(stream).expires_after(patience);
    beast::get_lowest_layer(stream).connect(net::ip::tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
    stream.handshake(net::ssl::stream_base::client);
    RawExchange out;
    // A provider that refuses early may stop reading: what it answered is
    // still read below, which is the point.
    beast::error_code write_error;
    net::write(stream, net::buffer(bytes), write_error);
    out.write_error = write_error.message();
    if (!write_error) out.write_error.clear();
    char buffer[4096];
    for (;;) {
        beast::get_lowest_layer(stream).expires_after(patience);
        beast::error_code ec;
        const std::size_t n = stream.read_some(net::buffer(buffer), ec);
        out.received.append(buffer, n);
        if (ec) {
            out.closed = ec != beast::error::timeout;
            break;
        }
    }
    return out;
}

}  // namespace umf::test
