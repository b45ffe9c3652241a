// The provider's TLS identity: a self-signed EC P-256 certificate and its key,
// made on first start and kept in the configuration directory, so the
// fingerprint in a pairing URL stays valid across restarts.
#pragma once

#include <filesystem>
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
    std::string certificate_pem;
    std::string private_key_pem;
    std::string fingerprint;  // SHA-256 of the certificate's DER, 64 lowercase hex digits
};

inline constexpr const char* kCertificateFile = "provider-cert.pem";
inline constexpr const char* kPrivateKeyFile = "provider-key.pem";

// A new key pair and a self-signed certificate for it (CN common_name,
// subjectAltName DNS:localhost and IP:127.0.0.1, valid ten years from a day
// ago, SHA-256 signature). Throws TlsIdentityError.
TlsIdentity create_tls_identity(const std::string& common_name = "umf-provider");

// The identity stored in `dir`, or a new one saved there (both files 0600)
// when there is none. An unreadable or mismatched pair is an error rather
// than silently replaced, since replacing it breaks every paired requester.
// Throws TlsIdentityError (or ConfigError for the directory).
TlsIdentity load_or_create_tls_identity(const std::filesystem::path& dir);

// SHA-256 of the first certificate in `pem`, as 64 lowercase hex digits.
std::string certificate_fingerprint(const std::string& certificate_pem);

// TLS 1.2 and later, the identity's certificate and key.
void configure_server_context(boost::asio::ssl::context& context, const TlsIdentity& identity);

}  // namespace umf::provider
