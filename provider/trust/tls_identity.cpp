#include "provider/trust/tls_identity.hpp"

#include "native/openssl_error.hpp"

#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>

#include <boost/asio/ssl/context.hpp>

namespace umf::provider {

using native::take_openssl_error;

// The chain and key in OpenSSL's form, freed with the last handshake using them.
struct CurrentIdentity::Parsed {
    X509* leaf = nullptr;
    STACK_OF(X509)* chain = nullptr;  // what follows the leaf
    EVP_PKEY* key = nullptr;
    ~Parsed() {
        X509_free(leaf);
        sk_X509_pop_free(chain, X509_free);
        EVP_PKEY_free(key);
    }
};

namespace {

std::shared_ptr<const CurrentIdentity::Parsed> parse(const TlsIdentity& identity) {
    auto parsed = std::make_shared<CurrentIdentity::Parsed>();
    BIO* bio = BIO_new_mem_buf(identity.certificate_pem.data(), static_cast<int>(identity.certificate_pem.size()));
    if (!bio) throw TlsIdentityError("cannot allocate a BIO");
    parsed->leaf = PEM_read_bio_X509(bio, nullptr, nullptr, nullptr);
    parsed->chain = sk_X509_new_null();
    while (X509* next = PEM_read_bio_X509(bio, nullptr, nullptr, nullptr)) sk_X509_push(parsed->chain, next);
    ERR_clear_error();
    BIO_free(bio);
    bio = BIO_new_mem_buf(identity.private_key_pem.data(), static_cast<int>(identity.private_key_pem.size()));
    parsed->key = bio ? PEM_read_bio_PrivateKey(bio, nullptr, nullptr, nullptr) : nullptr;
    BIO_free(bio);
    if (!parsed->leaf || !parsed->chain) throw TlsIdentityError("the served certificate cannot be read" + take_openssl_error());
    if (!parsed->key) throw TlsIdentityError("the served key cannot be read" + take_openssl_error());
    if (X509_check_private_key(parsed->leaf, parsed->key) != 1)
        throw TlsIdentityError("the served key does not belong to its certificate" + take_openssl_error());
    return parsed;
}

// Called by OpenSSL at the start of each handshake: the connection gets the
// identity current then, so a re-issued certificate takes effect at once.
int use_current_identity(SSL* ssl, void* arg) {
    const auto parsed = static_cast<const CurrentIdentity*>(arg)->get();
    return SSL_use_cert_and_key(ssl, parsed->leaf, parsed->key, parsed->chain, 1) == 1 ? 1 : 0;
}

}  // namespace

CurrentIdentity::CurrentIdentity(const TlsIdentity& identity) : parsed_(parse(identity)) {}
CurrentIdentity::~CurrentIdentity() = default;

void CurrentIdentity::replace(const TlsIdentity& identity) {
    auto parsed = parse(identity);
    std::lock_guard lock(mutex_);
    parsed_ = std::move(parsed);
}

std::shared_ptr<const CurrentIdentity::Parsed> CurrentIdentity::get() const {
    std::lock_guard lock(mutex_);
    return parsed_;
}

void configure_server_context(boost::asio::ssl::context& context, CurrentIdentity& current) {
    namespace ssl = boost::asio::ssl;
    context.set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 | ssl::context::no_sslv3 |
                        ssl::context::no_tlsv1 | ssl::context::no_tlsv1_1 | ssl::context::single_dh_use);
    SSL_CTX_set_cert_cb(context.native_handle(), use_current_identity, &current);
    // An idle connection keeps no OpenSSL read or write buffer (about 34 KiB
    // of the per-connection memory in docs/BENCHMARKS.md).
    SSL_CTX_set_mode(context.native_handle(), SSL_MODE_RELEASE_BUFFERS);
}

}  // namespace umf::provider
