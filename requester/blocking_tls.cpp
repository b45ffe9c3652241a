#include "requester/blocking_tls.hpp"

#include <fcntl.h>
#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ssl/context.hpp>
#include <cerrno>
#include <cstring>

#include "native/record_buffer.hpp"
#include "requester/transfer_text.hpp"

namespace umf::requester {

namespace {

// OpenSSL reads this much from the socket at once when it can: a few dozen
// records a system call instead of two calls for each (header, then body).
constexpr int kReadAheadBytes = 256 * 1024;

void set_socket_timeouts(int fd, std::chrono::milliseconds limit) {
    timeval tv{};
    tv.tv_sec = static_cast<time_t>(limit.count() / 1000);
    tv.tv_usec = static_cast<suseconds_t>((limit.count() % 1000) * 1000);
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
}

int verify_against_pin(int, X509_STORE_CTX* store) {
    auto* ssl = static_cast<SSL*>(X509_STORE_CTX_get_ex_data(store, SSL_get_ex_data_X509_STORE_CTX_idx()));
    auto* pin = static_cast<PinCheck*>(SSL_get_app_data(ssl));
    return pin && pin_verdict(store, *pin) ? 1 : 0;
}

}  // namespace

BlockingTls::BlockingTls(const protocol::PairingUrl& url, const NetTimeouts& timeouts, std::chrono::milliseconds idle) {
    // The TCP connection is made as every other one (address, then name);
    // the socket is then taken over from Asio.
    ReachedHost reached;
    boost::asio::ssl::context tls = make_pinned_client_context();
    {
        boost::asio::io_context io;
        TlsStream stream(io.get_executor(), tls);
        reached = connect_tcp(io, stream, url, timeouts);
        fd_.reset(boost::beast::get_lowest_layer(stream).socket().release());
    }
    const int flags = ::fcntl(fd_.get(), F_GETFL);
    if (flags < 0 || ::fcntl(fd_.get(), F_SETFL, flags & ~O_NONBLOCK) != 0)
        throw connection_failure(std::string("cannot use the connection: ") + std::strerror(errno));
    ssl_.reset(SSL_new(tls.native_handle()));
    if (!ssl_ || SSL_set_fd(ssl_.get(), fd_.get()) != 1) throw connection_failure("cannot start TLS");
    SSL* ssl = ssl_.get();
    // SNI only for names: RFC 6066 leaves addresses out.
    if (!reached.is_ip && !SSL_set_tlsext_host_name(ssl, reached.host.c_str()))
        throw connection_failure("cannot set the TLS server name " + reached.host);
    PinCheck pin;
    pin.expected = url.fingerprint;
    SSL_set_app_data(ssl, &pin);
    SSL_set_verify(ssl, SSL_VERIFY_PEER, verify_against_pin);
    SSL_set_read_ahead(ssl, 1);
    SSL_set_default_read_buffer_len(ssl, kReadAheadBytes);

    set_socket_timeouts(fd_.get(), timeouts.handshake);
    const int shaken = SSL_connect(ssl);
    SSL_set_app_data(ssl, nullptr);
    if (pin.mismatch) throw certificate_failure(url, pin.seen);
    if (shaken != 1) {
        failed(shaken);
        throw connection_failure("the TLS handshake with " + url.authority() + " " +
                                 (timed_out_ ? "did not finish within " + seconds_text(timeouts.handshake)
                                             : "failed: " + error_));
    }
    check_pinned_peer(ssl, url);
    // From here the records OpenSSL writes wait in memory and go to the
    // socket together (native/record_buffer.hpp); the socket BIO stays for reading.
    BIO* out = native::new_record_buffer_bio();
    if (!out) throw connection_failure("cannot start TLS");
    SSL_set0_wbio(ssl, out);
    out_ = &native::record_buffer_of(out);
    set_socket_timeouts(fd_.get(), idle);
}

BlockingTls::~BlockingTls() = default;

void BlockingTls::set_idle(std::chrono::milliseconds idle) { set_socket_timeouts(fd_.get(), idle); }

void BlockingTls::SslFree::operator()(ssl_st* ssl) const { SSL_free(ssl); }

BlockingTls::Socket::~Socket() { reset(-1); }

void BlockingTls::Socket::reset(int fd) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
}

bool BlockingTls::failed(int result) {
    const int kind = SSL_get_error(ssl_.get(), result);
    const int err = errno;
    timed_out_ = false;
    if (kind == SSL_ERROR_SYSCALL && (err == EAGAIN || err == EWOULDBLOCK)) {
        timed_out_ = true;
        error_ = "nothing arrived in time";
    } else if (kind == SSL_ERROR_SYSCALL && err != 0) {
        error_ = std::strerror(err);
    } else if (const unsigned long e = ERR_peek_last_error()) {
        char text[256];
        ERR_error_string_n(e, text, sizeof text);
        error_ = ERR_reason_error_string(e) ? ERR_reason_error_string(e) : text;
    } else {
        error_ = "the connection was closed";
    }
    ERR_clear_error();
    return false;
}

long BlockingTls::read_some(char* data, std::size_t size) {
    std::size_t n = 0;
    errno = 0;
    const int r = SSL_read_ex(ssl_.get(), data, size, &n);
    // Reading can make TLS answer (a key update): that goes out at once.
    if (out_->waiting() > 0 && !send_records()) return -1;
    if (r == 1) return static_cast<long>(n);
    if (SSL_get_error(ssl_.get(), r) == SSL_ERROR_ZERO_RETURN) return 0;
    failed(r);
    return -1;
}

bool BlockingTls::write_all(const char* data, std::size_t size) {
    while (size > 0) {
        std::size_t n = 0;
        errno = 0;
        const int r = SSL_write_ex(ssl_.get(), data, size, &n);  // into memory: it does not wait
        if (r != 1) return failed(r);
        data += n;
        size -= n;
    }
    return send_records();
}

bool BlockingTls::send_records() {
    while (out_->waiting() > 0) {
        const ssize_t n = ::send(fd_.get(), out_->data.get() + out_->sent, out_->waiting(), MSG_NOSIGNAL);
        if (n > 0) {
            out_->took(static_cast<std::size_t>(n));
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        timed_out_ = n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
        error_ = timed_out_ ? "nothing was taken in time" : n < 0 ? std::strerror(errno) : "the connection was closed";
        return false;
    }
    return true;
}

}  // namespace umf::requester
