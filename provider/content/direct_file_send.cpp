#include "provider/content/direct_file_send.hpp"

#include <openssl/bio.h>
#include <openssl/ssl.h>
#include <sys/socket.h>

#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cerrno>

#include "native/record_buffer.hpp"
#include "provider/content/verified_file_reader.hpp"

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
          idle_(idle),
          timer_(beast::get_lowest_layer(exchange_->stream()).socket().get_executor()),
          done_(std::move(done)) {}

    void start() {
        SSL* ssl = exchange_->stream().native_handle();
        // The stream's BIO pair stays for reading; what SSL writes goes to a
        // buffer this sender empties into the socket (native/record_buffer.hpp).
        BIO* out = native::new_record_buffer_bio();
        if (!out) return finish(beast::error_code(ENOMEM, boost::system::generic_category()));
        SSL_set_bio(ssl, SSL_get_rbio(ssl), out);
        out_ = &native::record_buffer_of(out);
        // A piece at a time into records, and their buffer kept: the stream's
        // modes suit a socket that may take part of a write, not a buffer.
        SSL_clear_mode(ssl, SSL_MODE_ENABLE_PARTIAL_WRITE | SSL_MODE_RELEASE_BUFFERS);
        beast::get_lowest_layer(exchange_->stream()).expires_never();
        reader_ = std::make_unique<VerifiedFileReader>(
            body_, [weak = weak_from_this(), executor = timer_.get_executor()] {
                // On the reader's thread: only the news goes to the strand.
                boost::asio::post(executor, [weak] {
                    if (auto self = weak.lock()) {
                        self->kept_while_reading_.reset();
                        self->pump();
                    }
                });
            });
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

    // Moves bytes until the socket is full (then waits for it), the next
    // piece is not read yet (the reader calls back), or all is sent:
    // a piece of plaintext into records, records out to the socket a
    // quarter of a megabyte at a time, the next piece when both are done
    // with.
    void pump() {
        SSL* ssl = exchange_->stream().native_handle();
        for (;;) {
            if (ended_) return;
            if (exchange_->stopping()) return finish(boost::asio::error::operation_aborted);
            if (piece_.size > 0) {
                std::size_t n = 0;  // into memory: it never waits
                if (SSL_write_ex(ssl, piece_.data, piece_.size, &n) != 1)
                    return finish(beast::error_code(EPROTO, boost::system::generic_category()));
                piece_.data += n;
                piece_.size -= n;
                if (piece_.size == 0) reader_->release();
                continue;
            }
            const std::size_t waiting = out_->waiting();
            if (waiting > 0 && (waiting >= kSendBytes || read_all_ || out_->sent > 0)) {
                if (!send_some()) return;
                continue;
            }
            if (!read_all_) {
                beast::error_code ec;
                switch (reader_->take(piece_, ec)) {
                case VerifiedFileReader::Next::piece: continue;
                case VerifiedFileReader::Next::waiting:
                    // Nothing else holds this sender until the reader calls back.
                    kept_while_reading_ = shared_from_this();
                    return;
                case VerifiedFileReader::Next::end: read_all_ = true; continue;
                case VerifiedFileReader::Next::failed: return finish(ec);
                }
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

    // One send of the records waiting; false when the socket is full (a
    // wait for it is armed) or the connection failed (finished).
    bool send_some() {
        auto& socket = beast::get_lowest_layer(exchange_->stream()).socket();
        const ssize_t n = ::send(socket.native_handle(), out_->data.get() + out_->sent, out_->waiting(),
                                 MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            out_->took(static_cast<std::size_t>(n));
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
        reader_.reset();  // its thread stops now, not when the last handler lets go
        kept_while_reading_.reset();  // the caller holds this sender still
        exchange_->drop();
        done_(ec);
    }

    std::shared_ptr<HttpExchange> exchange_;
    VerifiedFileBody::value_type body_;
    std::unique_ptr<VerifiedFileReader> reader_;  // reads body_
    std::shared_ptr<DirectSend> kept_while_reading_;  // this, while waiting for the reader
    std::chrono::seconds idle_;
    boost::asio::steady_timer timer_;
    std::function<void(beast::error_code)> done_;
    native::RecordBuffer* out_ = nullptr;  // the write BIO's, owned by the SSL object
    VerifiedFileReader::Piece piece_;  // taken, not yet all encrypted
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
