// One pinned TLS connection to a provider driven by blocking calls, for the
// bulk of a large transfer. An asynchronous read costs a turn of the event
// loop, a timer and an executor copy for every 16 KiB record; here OpenSSL
// reads ahead from the socket many records at a time and each call moves as
// many bytes as the caller asks, and a write's records go to the socket in
// one send rather than a system call each. The socket's own receive and send timeouts
// are the idle limit. Connected and pinned as connect_pinned does (the same
// address-then-name order, the same pin check at the leaf and after).
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

#include <boost/asio/buffer.hpp>
#include <boost/beast/http/error.hpp>

#include "native/record_buffer.hpp"
#include "requester/pinned_tls.hpp"
#include "shared/protocol/pairing_url.hpp"

namespace umf::requester {

class BlockingTls {
public:
    // Connects (timeouts.connect), shakes hands (timeouts.handshake) and
    // then waits at most `idle` for each read or write. Throws GrabFailure
    // "connection" or "certificate" as connect_pinned does.
    BlockingTls(const protocol::PairingUrl& url, const NetTimeouts& timeouts, std::chrono::milliseconds idle);
    ~BlockingTls();
    BlockingTls(const BlockingTls&) = delete;
    BlockingTls& operator=(const BlockingTls&) = delete;

    // Up to `size` bytes into `data`: as many as are there (at least one),
    // 0 when the provider closed the connection, -1 on an error (error()
    // says which; timed_out() when nothing came within the idle limit).
    long read_some(char* data, std::size_t size);
    // All of `size` bytes; false on an error as read_some.
    bool write_all(const char* data, std::size_t size);

    const std::string& error() const { return error_; }
    bool timed_out() const { return timed_out_; }
    // The limit for each read and write from now on.
    void set_idle(std::chrono::milliseconds idle);

private:
    // Records why a call that returned `result` failed; false.
    bool failed(int result);
    // The records OpenSSL has written, to the socket; false as failed().
    bool send_records();

    struct SslFree {
        void operator()(ssl_st* ssl) const;
    };
    class Socket {
    public:
        Socket() = default;
        Socket(const Socket&) = delete;
        Socket& operator=(const Socket&) = delete;
        ~Socket();
        void reset(int fd);
        int get() const { return fd_; }

    private:
        int fd_ = -1;
    };
    // Declared before ssl_: the SSL object goes first, then the socket.
    Socket fd_;
    std::unique_ptr<ssl_st, SslFree> ssl_;
    native::RecordBuffer* out_ = nullptr;  // the write BIO's, owned by ssl_
    std::string error_;
    bool timed_out_ = false;
};

// Feeds `parser` with what arrives on `tls` until `enough(parser)` (the
// header, or the whole message); what was read past the parser's last
// byte stays in `carried` from `used` on. False with `why` when the
// connection broke or ended first, or the parser refused the bytes.
template <class Parser, class Enough>
bool read_message(BlockingTls& tls, Parser& parser, Enough enough, std::string& carried, std::size_t& used,
                  std::string& why) {
    char piece[16 * 1024];
    for (;;) {
        boost::beast::error_code ec;
        if (used < carried.size()) used += parser.put(boost::asio::buffer(carried.data() + used, carried.size() - used), ec);
        if (enough(parser)) return true;
        if (ec && ec != boost::beast::http::error::need_more) {
            why = "cannot read the answer: " + ec.message();
            return false;
        }
        const long n = tls.read_some(piece, sizeof piece);
        if (n <= 0) {
            why = n == 0 ? "the provider closed the connection before it answered" : "cannot read the answer: " + tls.error();
            return false;
        }
        carried.append(piece, static_cast<std::size_t>(n));
    }
}

}  // namespace umf::requester
