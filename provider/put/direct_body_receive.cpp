#include "provider/put/direct_body_receive.hpp"

#include <openssl/bio.h>
#include <openssl/ssl.h>
#include <sys/socket.h>

#include <boost/asio/steady_timer.hpp>
#include <cerrno>
#include <vector>

namespace umf::provider {

namespace {

namespace beast = boost::beast;

// One recv takes at most this much ciphertext.
constexpr std::size_t kReceiveBytes = 256 * 1024;
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
          received_(kReceiveBytes),
          piece_(kPieceBytes) {}

    ~DirectReceive() { give_back(); }

    void start() {
        SSL* ssl = exchange_->stream().native_handle();
        in_ = BIO_new(BIO_s_mem());
        if (!in_) return finish(beast::error_code(ENOMEM, boost::system::generic_category()));
        // The stream's BIO is kept (one reference of ours) to be put back.
        stream_bio_ = SSL_get_rbio(ssl);
        BIO_up_ref(stream_bio_);
        SSL_set0_rbio(ssl, in_);
        beast::get_lowest_layer(exchange_->stream()).expires_never();
        arm_timer();
        pump();
    }

private:
    void arm_timer() {
        timer_.expires_after(idle_);
        timer_.async_wait([weak = weak_from_this()](beast::error_code ec) {
            if (ec) return;
            if (auto self = weak.lock()) self->finish(beast::error::timeout);
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
            if (SSL_read_ex(ssl, piece_.data() + filled_, want, &n) == 1) {
                filled_ += n;
                left_ -= n;
                continue;
            }
            const int why = SSL_get_error(ssl, 0);
            if (why == SSL_ERROR_ZERO_RETURN) return finish(boost::asio::error::eof);
            if (why != SSL_ERROR_WANT_READ) return finish(beast::error_code(EPROTO, boost::system::generic_category()));
            if (!receive_some()) return;
        }
    }

    // One recv into the memory BIO; false when the socket is empty (a wait
    // is armed) or the connection ended (finished).
    bool receive_some() {
        auto& socket = beast::get_lowest_layer(exchange_->stream()).socket();
        const ssize_t n = ::recv(socket.native_handle(), received_.data(), received_.size(), MSG_DONTWAIT);
        if (n > 0) {
            if (BIO_write(in_, received_.data(), static_cast<int>(n)) != n) {
                finish(beast::error_code(ENOMEM, boost::system::generic_category()));
                return false;
            }
            arm_timer();
            return true;
        }
        if (n < 0 && errno == EINTR) return true;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            socket.async_wait(boost::asio::socket_base::wait_read, [self = shared_from_this()](beast::error_code ec) {
                if (ec) return self->finish(ec);
                self->pump();
            });
            return false;
        }
        finish(n == 0 ? beast::error_code(boost::asio::error::eof)
                      : beast::error_code(errno, boost::system::system_category()));
        return false;
    }

    // The stream reads through its own BIO again.
    void give_back() {
        if (!stream_bio_) return;
        SSL_set0_rbio(exchange_->stream().native_handle(), stream_bio_);  // our reference goes to it
        stream_bio_ = nullptr;
        in_ = nullptr;
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
    std::chrono::seconds idle_;
    boost::asio::steady_timer timer_;
    std::function<bool(const char*, std::size_t)> take_;
    std::function<void(beast::error_code)> done_;
    std::vector<char> received_;
    std::vector<char> piece_;
    std::size_t filled_ = 0;
    BIO* in_ = nullptr;           // owned by the SSL object while reading
    BIO* stream_bio_ = nullptr;   // the stream's, one reference held while reading
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
