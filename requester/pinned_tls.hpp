// TLS to a provider, trusted by the certificate's fingerprint from the
// pairing URL and by nothing else: the provider's certificate is
// self-signed, and a CA-signed certificate for the same host must not be
// accepted instead (that would let anyone with a certificate for the name
// in between). Used by the WebSocket session and by downloads alike.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/beast/core/error.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/field.hpp>
#include <boost/beast/ssl/ssl_stream.hpp>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

#include "requester/grab_failure.hpp"
#include "shared/protocol/pairing_url.hpp"

struct x509_store_ctx_st;
struct ssl_st;

namespace umf::requester {

// Every network step has a deadline, so a provider that went away (or a
// firewall that drops packets) ends a grab with a message instead of a hang.
struct NetTimeouts {
    std::chrono::milliseconds connect{5000};
    std::chrono::milliseconds handshake{5000};   // TLS, then the WebSocket upgrade, each
    std::chrono::milliseconds reply{10000};      // welcome, target, content
    std::chrono::milliseconds download_idle{30000};
};

using TlsStream = boost::beast::ssl_stream<boost::beast::tcp_stream>;

// A client context with no trust store: verification is left entirely to
// the pin that connect_pinned installs on each stream.
boost::asio::ssl::context make_pinned_client_context();

// Runs io until `done` is set or the deadline passes; then calls `cancel`
// and lets the cancelled operation finish (up to 2 s). False on a timeout.
// The caller's operation must be outstanding, or io have a work guard.
bool run_until(boost::asio::io_context& io, const bool& done, std::chrono::steady_clock::time_point deadline,
               const std::function<void()>& cancel);

// One read or write on `stream` with a deadline of `timeout` (the socket's
// own expiry, and run_until's as a backstop): `start(handler)` begins it.
// Returns the error it ended with, beast::error::timeout when it did not end.
template <class Start>
boost::beast::error_code run_step(boost::asio::io_context& io, TlsStream& stream, std::chrono::milliseconds timeout,
                                  Start start) {
    bool done = false;
    boost::beast::error_code ec;
    boost::beast::get_lowest_layer(stream).expires_after(timeout);
    start([&](boost::beast::error_code e, std::size_t) {
        ec = e;
        done = true;
    });
    if (!run_until(io, done, std::chrono::steady_clock::now() + timeout + std::chrono::seconds(1),
                   [&] { boost::beast::get_lowest_layer(stream).close(); }))
        return boost::beast::error::timeout;
    return ec;
}

// What the verify callback saw, for a message that tells a wrong pin from a
// network failure.
struct PinCheck {
    std::string expected;  // the pairing URL's fingerprint
    std::string seen;      // the leaf's fingerprint when it did not match
    bool mismatch = false;
};

// The verify callback's answer for one certificate of the provider's chain:
// the pin decides at the leaf; the rest passes. Records a mismatch in `pin`.
bool pin_verdict(x509_store_ctx_st* store, PinCheck& pin);

// After a handshake: throws GrabFailure "certificate" unless the session's
// own chain satisfies the URL's pin, so no path through OpenSSL skips it.
void check_pinned_peer(ssl_st* ssl, const protocol::PairingUrl& url);

// GrabFailure "connection" and "certificate" (seen: the fingerprint shown).
GrabFailure connection_failure(const std::string& message);
GrabFailure certificate_failure(const protocol::PairingUrl& url, const std::string& seen);

// Where connect_tcp reached the provider: the URL's address, or the
// screen's .local name when the address did not answer.
struct ReachedHost {
    std::string host;
    bool is_ip = false;
};

// Connects the stream's socket to the URL's address (timeouts.connect),
// else to its .local name. Throws GrabFailure "connection".
ReachedHost connect_tcp(boost::asio::io_context& io, TlsStream& stream, const protocol::PairingUrl& url,
                        const NetTimeouts& timeouts);

// Resolves the URL's host and connects to it (timeouts.connect), else to the
// URL's .local name, and completes the TLS handshake (timeouts.handshake)
// with SNI for host names, accepting the peer
// only when its chain satisfies the pin url.fingerprint. Throws GrabFailure:
// "connection" when the provider cannot be reached, "certificate" when it
// shows another certificate (nothing has been sent to it then).
void connect_pinned(boost::asio::io_context& io, TlsStream& stream, const protocol::PairingUrl& url,
                    const NetTimeouts& timeouts);

// "umf-requester/VERSION", what every connection says it is.
std::string user_agent();

// One HTTPS exchange with a provider (a download, an upload): its own
// io_context and the pinned TLS stream, connected by the constructor (which
// throws as connect_pinned does), and the request headers every such
// exchange sends: Host, User-Agent, Connection: close.
struct PinnedExchange {
    PinnedExchange(const protocol::PairingUrl& url, const NetTimeouts& timeouts)
        : tls(make_pinned_client_context()), stream(io.get_executor(), tls) {
        connect_pinned(io, stream, url, timeouts);
    }
    template <class Request>
    static void set_headers(Request& request, const protocol::PairingUrl& url) {
        request.set(boost::beast::http::field::host, url.authority());
        request.set(boost::beast::http::field::user_agent, user_agent());
        request.set(boost::beast::http::field::connection, "close");
    }

    boost::asio::io_context io;
    boost::asio::ssl::context tls;
    TlsStream stream;
};

}  // namespace umf::requester
