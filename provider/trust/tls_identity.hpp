// The provider's TLS identity: the chain it serves and that chain's key,
// and the fingerprint a pairing URL pins. Made and kept here
// (tls_identity_store.hpp), served by net/server.hpp, and replaced while serving
// when the serving certificate is issued again, for the connections that
// come after (CurrentIdentity).
#pragma once

#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace boost::asio::ssl {
class context;
}

namespace umf::provider {

class TlsIdentityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct TlsIdentity {
    // The serving certificate, then its root (then, for a directory from
    // before roots, the certificate older pairings pin), as PEM.
    std::string certificate_pem;
    std::string private_key_pem;  // the serving certificate's key
    std::string fingerprint;      // what pairing pins: SHA-256 of the root's DER, 64 lowercase hex digits
};

// The identity new connections are served with, parsed once; replace() is
// safe while handshakes run on other threads.
class CurrentIdentity {
public:
    struct Parsed;
    // Throws TlsIdentityError when the chain or the key cannot be read or
    // do not belong together.
    explicit CurrentIdentity(const TlsIdentity& identity);
    ~CurrentIdentity();
    void replace(const TlsIdentity& identity);
    std::shared_ptr<const Parsed> get() const;

private:
    mutable std::mutex mutex_;
    std::shared_ptr<const Parsed> parsed_;
};

// TLS 1.2 and later; each handshake is served `current`'s identity of that
// moment. `current` must outlive the context.
void configure_server_context(boost::asio::ssl::context& context, CurrentIdentity& current);

}  // namespace umf::provider
