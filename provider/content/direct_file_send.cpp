#include "provider/content/direct_file_send.hpp"

#include <openssl/bio.h>
#include <openssl/buffer.h>
#include <openssl/ssl.h>
#include <sys/socket.h>

#include <boost/asio/steady_timer.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>
#include <cerrno>

namespace umf::provider {

namespace {

namespace beast = boost::beast;
namespace http = beast::http;

// Ciphertext gathered before it goes to the socket.
constexpr std::size_t kSendBytes = 256 * 1024;

class DirectSend : public std::enable_shared_from_this<DirectSend> {
public:
    DirectSend(std::shared_ptr<HttpExchange> exchange, VerifiedFileBody::value_type body, std::chrono::seconds idle,
               std::function<void(beast::error_code)> done)
        : exchange_(std::move(exchange)),
          body_(std::move(body)),
          writer_(header_, body_),
          idle_(idle),
          timer_(beast::get_lowest_layer(exchange_->stream()).socket().get_executor()),
          done_(std::move(done)) {}

    void start() {
        SSL* ssl = exchange_->stream().native_handle();
        // The stream's BIO pair stays for reading; what SSL writes goes to a
        // memory BIO this sender empties into the socket.
        BIO* out = BIO_new(BIO_s_mem());
        if (!out) return finish(beast::error_code(ENOMEM, boost::system::generic_category()));
        SSL_set_bio(ssl, SSL_get_rbio(ssl), out);
        out_ = out;
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

    // Moves bytes until the socket is full (then waits for it) or all is
    // sent: plaintext into records in memory, records out to the socket a
    // quarter of a megabyte at a time, the next piece of the file when both
    // are done with.
    void pump() {
        SSL* ssl = exchange_->stream().native_handle();
        for (;;) {
            if (ended_) return;
            if (exchange_->stopping()) return finish(boost::asio::error::operation_aborted);
            if (plain_size_ > 0) {
                std::size_t n = 0;  // into memory: it never waits
                if (SSL_write_ex(ssl, plain_, plain_size_, &n) != 1)
                    return finish(beast::error_code(EPROTO, boost::system::generic_category()));
                plain_ += n;
                plain_size_ -= n;
                continue;
            }
            const std::size_t waiting = ciphertext_waiting();
            if (waiting > 0 && (waiting >= kSendBytes || read_all_ || sent_ > 0)) {
                if (!send_some()) return;
                continue;
            }
            if (!read_all_) {
                beast::error_code ec;
                const auto piece = writer_.get(ec);
                if (ec) return finish(ec);
                if (!piece) {
                    read_all_ = true;
                    continue;
                }
                plain_ = static_cast<const char*>(piece->first.data());
                plain_size_ = piece->first.size();
                read_all_ = !piece->second;
                continue;
            }
            if (!closing_) {
                // close_notify, so the peer tells the end from a cut.
                closing_ = true;
                SSL_shutdown(ssl);
                continue;
            }
            return finish({});
        }
    }

    std::size_t ciphertext_waiting() const {
        BUF_MEM* buffered = nullptr;
        BIO_get_mem_ptr(out_, &buffered);
        return buffered ? buffered->length - sent_ : 0;
    }

    // One send of what the memory BIO holds; false when the socket is full
    // (a wait for it is armed) or the connection failed (finished).
    bool send_some() {
        auto& socket = beast::get_lowest_layer(exchange_->stream()).socket();
        BUF_MEM* buffered = nullptr;
        BIO_get_mem_ptr(out_, &buffered);
        const ssize_t n = ::send(socket.native_handle(), buffered->data + sent_, buffered->length - sent_,
                                 MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            sent_ += static_cast<std::size_t>(n);
            if (sent_ == buffered->length) {
                (void)BIO_reset(out_);
                sent_ = 0;
            }
            arm_timer();
            return true;
        }
        if (n < 0 && errno == EINTR) return true;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            socket.async_wait(boost::asio::socket_base::wait_write, [self = shared_from_this()](beast::error_code ec) {
                if (ec) return self->finish(ec);
                self->pump();
            });
            return false;
        }
        finish(beast::error_code(n < 0 ? errno : EPIPE, boost::system::system_category()));
        return false;
    }

    void finish(beast::error_code ec) {
        if (ended_) return;
        ended_ = true;
        timer_.cancel();
        exchange_->drop();
        done_(ec);
    }

    std::shared_ptr<HttpExchange> exchange_;
    http::response_header<> header_;
    VerifiedFileBody::value_type body_;
    VerifiedFileBody::writer writer_;
    std::chrono::seconds idle_;
    boost::asio::steady_timer timer_;
    std::function<void(beast::error_code)> done_;
    BIO* out_ = nullptr;  // owned by the SSL object
    std::size_t sent_ = 0;  // of the memory BIO's bytes
    const char* plain_ = nullptr;
    std::size_t plain_size_ = 0;
    bool read_all_ = false;
    bool closing_ = false;
    bool ended_ = false;
};

}  // namespace

void send_file_direct(std::shared_ptr<HttpExchange> exchange, VerifiedFileBody::value_type body,
                      std::chrono::seconds idle, std::function<void(beast::error_code)> done) {
    std::make_shared<DirectSend>(std::move(exchange), std::move(body), idle, std::move(done))->start();
}

}  // namespace umf::provider
