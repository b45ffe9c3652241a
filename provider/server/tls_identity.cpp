#include "server/tls_identity.hpp"

#include "native/certificate_fingerprint.hpp"

#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/rand.h>
#include <openssl/x509.h>
#include <openssl/ssl.h>
#include <openssl/x509v3.h>

#include <boost/asio/buffer.hpp>
#include <boost/asio/ssl/context.hpp>
#include <memory>

#include "server/config_dir.hpp"

namespace umf::provider {

namespace {

template <class T, void (*Free)(T*)>
struct Deleter {
    void operator()(T* p) const { Free(p); }
};
using PKeyPtr = std::unique_ptr<EVP_PKEY, Deleter<EVP_PKEY, EVP_PKEY_free>>;
using X509Ptr = std::unique_ptr<X509, Deleter<X509, X509_free>>;
using BioPtr = std::unique_ptr<BIO, Deleter<BIO, BIO_free_all>>;
using ExtPtr = std::unique_ptr<X509_EXTENSION, Deleter<X509_EXTENSION, X509_EXTENSION_free>>;

[[noreturn]] void fail(const std::string& what) {
    std::string detail;
    if (unsigned long e = ERR_get_error(); e != 0) {
        char buf[256];
        ERR_error_string_n(e, buf, sizeof buf);
        detail = std::string(": ") + buf;
    }
    ERR_clear_error();
    throw TlsIdentityError(what + detail);
}

std::string bio_text(BIO* bio) {
    char* data = nullptr;
    const long n = BIO_get_mem_data(bio, &data);
    return n > 0 ? std::string(data, static_cast<std::size_t>(n)) : std::string();
}

BioPtr memory_bio(const std::string& text) {
    BioPtr bio(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
    if (!bio) fail("cannot allocate a BIO");
    return bio;
}

X509Ptr read_certificate(const std::string& pem) {
    auto bio = memory_bio(pem);
    X509Ptr cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
    if (!cert) fail("not a PEM certificate");
    return cert;
}

void add_extension(X509* cert, int nid, const char* value) {
    X509V3_CTX ctx;
    X509V3_set_ctx_nodb(&ctx);
    X509V3_set_ctx(&ctx, cert, cert, nullptr, nullptr, 0);
    ExtPtr ext(X509V3_EXT_conf_nid(nullptr, &ctx, nid, value));
    if (!ext || X509_add_ext(cert, ext.get(), -1) != 1) fail(std::string("cannot add the extension ") + value);
}

}  // namespace

std::string certificate_fingerprint(const std::string& certificate_pem) {
    X509Ptr cert = read_certificate(certificate_pem);
    std::string fp = native::certificate_fingerprint(cert.get());
    if (fp.empty()) fail("cannot encode the certificate");
    return fp;
}

TlsIdentity create_tls_identity(const std::string& common_name) {
    PKeyPtr key(EVP_EC_gen("P-256"));
    if (!key) fail("cannot generate an EC P-256 key");

    X509Ptr cert(X509_new());
    if (!cert) fail("cannot allocate a certificate");
    if (X509_set_version(cert.get(), X509_VERSION_3) != 1) fail("cannot set the certificate version");
    // A random positive 127-bit serial, so two identities never share one.
    unsigned char serial[16];
    if (RAND_bytes(serial, sizeof serial) != 1) fail("no random bytes");
    serial[0] &= 0x7f;
    BIGNUM* bn = BN_bin2bn(serial, sizeof serial, nullptr);
    if (!bn || !BN_to_ASN1_INTEGER(bn, X509_get_serialNumber(cert.get()))) {
        BN_free(bn);
        fail("cannot set the serial number");
    }
    BN_free(bn);
    if (!X509_gmtime_adj(X509_getm_notBefore(cert.get()), -24L * 3600) ||
        !X509_gmtime_adj(X509_getm_notAfter(cert.get()), 10L * 365 * 24 * 3600))
        fail("cannot set the validity");
    if (X509_set_pubkey(cert.get(), key.get()) != 1) fail("cannot set the public key");
    X509_NAME* name = X509_get_subject_name(cert.get());
    if (X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_UTF8,
                                   reinterpret_cast<const unsigned char*>(common_name.c_str()), -1, -1, 0) != 1 ||
        X509_set_issuer_name(cert.get(), name) != 1)
        fail("cannot set the name");
    add_extension(cert.get(), NID_basic_constraints, "critical,CA:FALSE");
    add_extension(cert.get(), NID_key_usage, "critical,digitalSignature");
    add_extension(cert.get(), NID_ext_key_usage, "serverAuth");
    add_extension(cert.get(), NID_subject_alt_name, "DNS:localhost,IP:127.0.0.1");
    if (X509_sign(cert.get(), key.get(), EVP_sha256()) <= 0) fail("cannot sign the certificate");

    TlsIdentity id;
    BioPtr cert_bio(BIO_new(BIO_s_mem()));
    BioPtr key_bio(BIO_new(BIO_s_mem()));
    if (!cert_bio || !key_bio || PEM_write_bio_X509(cert_bio.get(), cert.get()) != 1 ||
        PEM_write_bio_PrivateKey(key_bio.get(), key.get(), nullptr, nullptr, 0, nullptr, nullptr) != 1)
        fail("cannot write PEM");
    id.certificate_pem = bio_text(cert_bio.get());
    id.private_key_pem = bio_text(key_bio.get());
    id.fingerprint = certificate_fingerprint(id.certificate_pem);
    return id;
}

TlsIdentity load_or_create_tls_identity(const std::filesystem::path& dir) {
    ensure_config_dir(dir);
    const auto cert_path = dir / kCertificateFile, key_path = dir / kPrivateKeyFile;
    auto cert = read_small_file(cert_path);
    auto key = read_small_file(key_path);
    if (!cert && !key) {
        TlsIdentity id = create_tls_identity();
        // The key first: a certificate without its key would be the worse half.
        write_private_file(key_path, id.private_key_pem);
        write_private_file(cert_path, id.certificate_pem);
        return id;
    }
    if (!cert || !key)
        throw TlsIdentityError((cert ? key_path : cert_path).string() +
                               " is missing; remove the other file to make a new identity (paired requesters must pair again)");
    TlsIdentity id{*cert, *key, {}};
    try {
        id.fingerprint = certificate_fingerprint(id.certificate_pem);
    } catch (const TlsIdentityError& e) {
        throw TlsIdentityError(cert_path.string() + ": " + e.what());
    }
    X509Ptr x = read_certificate(id.certificate_pem);
    auto bio = memory_bio(id.private_key_pem);
    PKeyPtr pkey(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
    if (!pkey) fail(key_path.string() + ": not a PEM private key");
    if (X509_check_private_key(x.get(), pkey.get()) != 1)
        fail(key_path.string() + " does not belong to " + cert_path.string());
    return id;
}

void configure_server_context(boost::asio::ssl::context& context, const TlsIdentity& identity) {
    namespace ssl = boost::asio::ssl;
    context.set_options(ssl::context::default_workarounds | ssl::context::no_sslv2 | ssl::context::no_sslv3 |
                        ssl::context::no_tlsv1 | ssl::context::no_tlsv1_1 | ssl::context::single_dh_use);
    context.use_certificate_chain(boost::asio::buffer(identity.certificate_pem));
    context.use_private_key(boost::asio::buffer(identity.private_key_pem), ssl::context::pem);
    // An idle connection keeps no OpenSSL read or write buffer (about 34 KiB
    // of the per-connection memory in docs/BENCHMARKS.md).
    SSL_CTX_set_mode(context.native_handle(), SSL_MODE_RELEASE_BUFFERS);
}

}  // namespace umf::provider
