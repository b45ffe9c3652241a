// A TLS client context that trusts exactly the provider a pairing pins
// (docs/PROTOCOL.md, "Pairing"; native/certificate_pin.hpp), as requesters
// do: for the tests and benchmarks that talk to a real provider.
#pragma once

#include <openssl/x509.h>

#include <boost/asio/ssl/context.hpp>
#include <boost/asio/ssl/verify_context.hpp>
#include <string>

#include "native/certificate_pin.hpp"

namespace umf::test {

inline boost::asio::ssl::context pinned_client_context(const std::string& fingerprint) {
    namespace ssl = boost::asio::ssl;
    ssl::context ctx(ssl::context::tls_client);
    ctx.set_verify_mode(ssl::verify_peer);
    ctx.set_verify_callback([fingerprint](bool, ssl::verify_context& vc) {
        X509_STORE_CTX* store = vc.native_handle();
        if (X509_STORE_CTX_get_error_depth(store) != 0) return true;  // the pin decides at the leaf
        return umf::native::chain_satisfies_pin(X509_STORE_CTX_get_current_cert(store),
                                                X509_STORE_CTX_get0_untrusted(store), fingerprint);
    });
    return ctx;
}

}  // namespace umf::test
