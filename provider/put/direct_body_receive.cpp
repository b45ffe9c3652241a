#include "provider/put/direct_body_receive.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/ssl.h>
#include <sys/socket.h>

#include <boost/asio/steady_timer.hpp>
#include <cerrno>
#include <vector>

namespace umf::provider {

namespace {

namespace beast = boost::beast;

// OpenSSL reads this much ciphertext from the socket at once when it can.
constexpr int kReadAheadBytes = 256 * 1024;
// The body goes to the route in pieces of this size.
constexpr std::size_t kPieceBytes = 1 << 20;

class DirectReceive : public std::enable_shared_from_this<DirectReceive> {
public:
    DirectReceive(std::shared_ptr<HttpExchange> exchange, std::uint64_t length, std::chrono::seconds idle,
                  std::function<bool(const char*, std::size_t)> take, std::function<void(beast::error_code)> done)
        : exchange_(std::move(exchange)),
          left_(length),
          idle_(idle),
          timer_(beast::get_lowest_layer(exchange_->stream()).socket().get_executor()),
          take_(std::move(take)),
          done_(std::move(done)),
          piece_(kPieceBytes) {}

    ~DirectReceive() { give_back(); }

    void start() {
        SSL* ssl = exchange_->stream().native_handle();
        // OpenSSL reads the socket itself, many records a call, into its
        // own buffer (kept while the body comes, not released each time
        // it empties); the socket is non-blocking, so an empty one is
        // SSL_ERROR_WANT_READ.
        auto& socket = beast::get_lowest_layer(exchange_->stream()).socket();
        BIO* in = BIO_new_socket(socket.native_handle(), BIO_NOCLOSE);
        if (!in) return finish(beast::error_code(ENOMEM, boost::system::generic_category()));
        // The stream's BIO is kept (one reference of ours) to be put back.
        stream_bio_ = SSL_get_rbio(ssl);
        BIO_up_ref(stream_bio_);
        SSL_set0_rbio(ssl, in);
        modes_ = SSL_get_mode(ssl);
        SSL_clear_mode(ssl, SSL_MODE_RELEASE_BUFFERS);
        SSL_set_default_read_buffer_len(ssl, kReadAheadBytes);
        SSL_set_read_ahead(ssl, 1);
        beast::get_lowest_layer(exchange_->stream()).expires_never();
        arm_timer();
        pump();
    }

private:
    // The idle limit: the body ends with a timeout when `idle_` passes
    // without a byte of it; the timer is set again only when it rings
    // (a record at a time would cost a timer each).
    void arm_timer() {
        left_when_armed_ = left_;
        timer_.expires_after(idle_);
        timer_.async_wait([weak = weak_from_this()](beast::error_code ec) {
            if (ec) return;
            auto self = weak.lock();
            if (!self) return;
            if (self->left_ != self->left_when_armed_) return self->arm_timer();
            self->finish(beast::error::timeout);
        });
    }

    // Decrypts what has arrived into the piece, hands full pieces on, and
    // reads the socket when TLS needs more; waits on the reactor only when
    // the socket is empty.
    void pump() {
        SSL* ssl = exchange_->stream().native_handle();
        while (!ended_) {
            if (exchange_->stopping()) return finish(boost::asio::error::operation_aborted);
            if (filled_ == piece_.size() || (left_ == 0 && filled_ > 0)) {
                if (!take_(piece_.data(), filled_)) return finish(boost::asio::error::operation_aborted);
                filled_ = 0;
                continue;
            }
            if (left_ == 0) return finish({});
            const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(piece_.size() - filled_, left_));
            std::size_t n = 0;
            errno = 0;
            const int r = SSL_read_ex(ssl, piece_.data() + filled_, want, &n);
            if (r == 1) {
                filled_ += n;
                left_ -= n;
                continue;
            }
            const int why = SSL_get_error(ssl, r);
            if (why == SSL_ERROR_WANT_READ) return wait_for_bytes();
            if (why == SSL_ERROR_SYSCALL && errno == EINTR) continue;
            ERR_clear_error();
            // The peer closed (with or without close_notify) or sent what is not TLS.
            return finish(why == SSL_ERROR_ZERO_RETURN || (why == SSL_ERROR_SYSCALL && errno == 0)
                              ? beast::error_code(boost::asio::error::eof)
                              : beast::error_code(EPROTO, boost::system::generic_category()));
        }
    }

    // The socket is empty: pump again once it is readable.
    void wait_for_bytes() {
        auto& socket = beast::get_lowest_layer(exchange_->stream()).socket();
        socket.async_wait(boost::asio::socket_base::wait_read, [self = shared_from_this()](beast::error_code ec) {
            if (ec) return self->finish(ec);
            self->pump();
        });
    }

    // The stream reads through its own BIO again, as it did.
    void give_back() {
        if (!stream_bio_) return;
        SSL* ssl = exchange_->stream().native_handle();
        SSL_set0_rbio(ssl, stream_bio_);  // our reference goes to it; the socket BIO is freed
        SSL_set_read_ahead(ssl, 0);
        SSL_set_default_read_buffer_len(ssl, 0);  // OpenSSL's own size again
        SSL_set_mode(ssl, modes_);
        stream_bio_ = nullptr;
    }

    void finish(beast::error_code ec) {
        if (ended_) return;
        ended_ = true;
        timer_.cancel();
        give_back();
        done_(ec);
    }

    std::shared_ptr<HttpExchange> exchange_;
    std::uint64_t left_;
    std::uint64_t left_when_armed_ = 0;
    std::chrono::seconds idle_;
    boost::asio::steady_timer timer_;
    std::function<bool(const char*, std::size_t)> take_;
    std::function<void(beast::error_code)> done_;
    std::vector<char> piece_;
    std::size_t filled_ = 0;
    BIO* stream_bio_ = nullptr;   // the stream's, one reference held while reading
    long modes_ = 0;              // the SSL object's modes before
    bool ended_ = false;
};

}  // namespace

// Asio's stream can also hold ciphertext it read from the socket but could
// not yet put into its BIO pair (17 KiB): that happens only when the pair was
// filled up, and a read completes after TLS took one record (16 KiB and a
// little) from it, so the pair still holds some then. An empty pair means
// nothing waits in the stream either.
bool direct_receive_possible(HttpExchange& exchange) {
    SSL* ssl = exchange.stream().native_handle();
    return exchange.buffer().size() == 0 && SSL_pending(ssl) == 0 && BIO_ctrl_pending(SSL_get_rbio(ssl)) == 0;
}

void receive_body_direct(std::shared_ptr<HttpExchange> exchange, std::uint64_t length, std::chrono::seconds idle,
                         std::function<bool(const char*, std::size_t)> take,
                         std::function<void(beast::error_code)> done) {
    std::make_shared<DirectReceive>(std::move(exchange), length, idle, std::move(take), std::move(done))->start();
}

}  // namespace umf::provider
