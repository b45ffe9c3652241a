// A TLS client context that trusts exactly the certificate with the given
// SHA-256 fingerprint, as requesters pin the provider's (docs/PROTOCOL.md,
// "Pairing"): for the tests and benchmarks that talk to a real provider.
#pragma once

#include <openssl/x509.h>

#include <boost/asio/ssl/context.hpp>
#include <boost/asio/ssl/verify_context.hpp>
#include <string>

#include "native/certificate_fingerprint.hpp"
#include "server/tls_identity.hpp"

namespace umf::test {

inline boost::asio::ssl::context pinned_client_context(const std::string& fingerprint) {
    namespace ssl = boost::asio::ssl;
    ssl::context ctx(ssl::context::tls_client);
    ctx.set_verify_mode(ssl::verify_peer);
    ctx.set_verify_callback([fingerprint](bool, ssl::verify_context& vc) {
        X509_STORE_CTX* store = vc.native_handle();
        if (X509_STORE_CTX_get_error_depth(store) != 0) return false;
        X509* cert = X509_STORE_CTX_get_current_cert(store);
        unsigned char* der = nullptr;
        const int len = i2d_X509(cert, &der);
        if (len <= 0) return false;
        const bool ok = umf::native::der_fingerprint(der, static_cast<std::size_t>(len)) == fingerprint;
        OPENSSL_free(der);
        return ok;
    });
    return ctx;
}

}  // namespace umf::test
