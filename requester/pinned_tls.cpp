#include "requester/pinned_tls.hpp"

#include "native/certificate_fingerprint.hpp"
#include "native/certificate_pin.hpp"

#include <openssl/evp.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <memory>

#include "requester/cli.hpp"
#include "requester/grab_failure.hpp"

namespace umf::requester {

namespace {

namespace net = boost::asio;
namespace ssl = boost::asio::ssl;
namespace beast = boost::beast;
using Clock = std::chrono::steady_clock;

}  // namespace

GrabFailure connection_failure(const std::string& message) { return {"connection", message, kConnection}; }

GrabFailure certificate_failure(const protocol::PairingUrl& url, const std::string& seen) {
    return {"certificate",
            "the provider at " + url.authority() + " shows a certificate that the screen the pairing URL names did not issue (" +
                (seen.empty() ? std::string("none") : seen.substr(0, 16) + "...") + " instead of " +
                url.fingerprint.substr(0, 16) +
                "...); nothing was sent to it. Pair again if the provider was reinstalled; otherwise something "
                "on the network is in between",
            kConnection};
}

ssl::context make_pinned_client_context() {
    ssl::context ctx(ssl::context::tls_client);
    ctx.set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 | ssl::context::no_sslv3 |
                    ssl::context::no_tlsv1 | ssl::context::no_tlsv1_1);
    // Deliberately no set_default_verify_paths(): a CA never vouches here.
    ctx.set_verify_mode(ssl::verify_peer);
    return ctx;
}

bool run_until(net::io_context& io, const bool& done, Clock::time_point deadline,
               const std::function<void()>& cancel) {
    while (!done && Clock::now() < deadline) {
        if (io.stopped()) io.restart();
        io.run_one_until(deadline);
    }
    if (done) return true;
    cancel();
    const auto grace = Clock::now() + std::chrono::seconds(2);
    while (!done && Clock::now() < grace) {
        if (io.stopped()) io.restart();
        io.run_one_until(grace);
    }
    return false;
}

namespace {

// Resolves `host` and connects the stream's socket to it (timeouts.connect
// each); the reason when it could not, empty when connected.
std::string connect_to(net::io_context& io, TlsStream& stream, const std::string& host, unsigned short port,
                       const std::string& authority, const NetTimeouts& timeouts) {
    // Resolve (a name may take a DNS or mDNS round trip; an address resolves at once).
    net::ip::tcp::resolver resolver(io);
    net::ip::tcp::resolver::results_type endpoints;
    beast::error_code ec;
    bool done = false;
    resolver.async_resolve(host, std::to_string(port), net::ip::tcp::resolver::numeric_service,
                           [&](beast::error_code e, net::ip::tcp::resolver::results_type r) {
                               ec = e;
                               endpoints = std::move(r);
                               done = true;
                           });
    if (!run_until(io, done, Clock::now() + timeouts.connect, [&] { resolver.cancel(); }))
        return "cannot resolve " + host + ": no answer within " + std::to_string(timeouts.connect.count() / 1000) + " s";
    if (ec) return "cannot resolve " + host + ": " + ec.message();

    auto& tcp = beast::get_lowest_layer(stream);
    done = false;
    tcp.expires_after(timeouts.connect);
    tcp.async_connect(endpoints, [&](beast::error_code e, const net::ip::tcp::endpoint&) {
        ec = e;
        done = true;
    });
    if (!run_until(io, done, Clock::now() + timeouts.connect + std::chrono::seconds(1), [&] { tcp.close(); }) ||
        ec == beast::error::timeout)
        return "cannot connect to " + authority + ": no answer within " + std::to_string(timeouts.connect.count() / 1000) +
               " s (is the provider running?)";
    if (ec) return "cannot connect to " + authority + ": " + ec.message();
    return {};
}

}  // namespace

ReachedHost connect_tcp(net::io_context& io, TlsStream& stream, const protocol::PairingUrl& url,
                        const NetTimeouts& timeouts) {
    // The URL's address first (where the screen was when paired), then the
    // screen's .local name, which follows it to a new address. The pin, not
    // the name or the address, decides whom the token goes to.
    const std::string failed = connect_to(io, stream, url.host, url.port, url.authority(), timeouts);
    if (failed.empty()) return {url.host, url.host_is_ip};
    if (url.name.empty()) throw connection_failure(failed);
    beast::get_lowest_layer(stream).close();
    const std::string again = connect_to(io, stream, url.name, url.port, url.name + ":" + std::to_string(url.port), timeouts);
    if (!again.empty()) throw connection_failure(failed + "; " + again);
    return {url.name, false};
}

bool pin_verdict(X509_STORE_CTX* store, PinCheck& pin) {
    // The pin decides at the leaf, from the chain the provider sent; OpenSSL's
    // own verdict on the rest (a root no store knows: "untrusted") is ignored.
    if (X509_STORE_CTX_get_error_depth(store) != 0) return true;
    X509* leaf = X509_STORE_CTX_get_current_cert(store);
    if (native::chain_satisfies_pin(leaf, X509_STORE_CTX_get0_untrusted(store), pin.expected)) return true;
    pin.mismatch = true;
    pin.seen = native::certificate_fingerprint(leaf);
    return false;
}

void check_pinned_peer(SSL* ssl, const protocol::PairingUrl& url) {
    // The callback must have passed the leaf; checked again on the session's
    // own chain so no path through OpenSSL skips the pin.
    X509* peer = SSL_get1_peer_certificate(ssl);
    const bool pinned = native::chain_satisfies_pin(peer, SSL_get_peer_cert_chain(ssl), url.fingerprint);
    const std::string fp = native::certificate_fingerprint(peer);
    X509_free(peer);
    if (!pinned) throw certificate_failure(url, fp);
}

void connect_pinned(net::io_context& io, TlsStream& stream, const protocol::PairingUrl& url, const NetTimeouts& timeouts) {
    const ReachedHost reached = connect_tcp(io, stream, url, timeouts);
    auto& tcp = beast::get_lowest_layer(stream);
    beast::error_code ec;
    bool done = false;

    // SNI only for names: RFC 6066 leaves addresses out.
    if (!reached.is_ip && !SSL_set_tlsext_host_name(stream.native_handle(), reached.host.c_str()))
        throw connection_failure("cannot set the TLS server name " + reached.host);

    auto pin = std::make_shared<PinCheck>();
    pin->expected = url.fingerprint;
    stream.set_verify_mode(ssl::verify_peer);
    stream.set_verify_callback([pin](bool, ssl::verify_context& vc) { return pin_verdict(vc.native_handle(), *pin); });

    done = false;
    tcp.expires_after(timeouts.handshake);
    stream.async_handshake(ssl::stream_base::client, [&](beast::error_code e) {
        ec = e;
        done = true;
    });
    const bool finished =
        run_until(io, done, Clock::now() + timeouts.handshake + std::chrono::seconds(1), [&] { tcp.close(); });
    if (pin->mismatch) throw certificate_failure(url, pin->seen);
    if (!finished || ec == beast::error::timeout)
        throw connection_failure("the TLS handshake with " + url.authority() + " did not finish within " +
                                 std::to_string(timeouts.handshake.count() / 1000) + " s");
    if (ec) throw connection_failure("the TLS handshake with " + url.authority() + " failed: " + ec.message());

    try {
        check_pinned_peer(stream.native_handle(), url);
    } catch (const GrabFailure&) {
        tcp.close();
        throw;
    }
    tcp.expires_never();
}

std::string user_agent() { return "umf-requester/" UMF_VERSION; }

}  // namespace umf::requester
