#include "provider/trust/openssl_objects.hpp"

#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/rand.h>

#include "native/certificate_fingerprint.hpp"
#include "native/openssl_error.hpp"
#include "provider/trust/tls_identity.hpp"

namespace umf::provider {

namespace {

using ExtPtr = std::unique_ptr<X509_EXTENSION, OpenSslFree<X509_EXTENSION, X509_EXTENSION_free>>;

BioPtr memory_bio(const std::string& text) {
    BioPtr bio(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
    if (!bio) throw_openssl_error("cannot allocate a BIO");
    return bio;
}

std::string bio_text(BIO* bio) {
    char* data = nullptr;
    const long n = BIO_get_mem_data(bio, &data);
    return n > 0 ? std::string(data, static_cast<std::size_t>(n)) : std::string();
}

}  // namespace

void throw_openssl_error(const std::string& what) { throw TlsIdentityError(what + native::take_openssl_error()); }

X509Ptr read_certificate(const std::string& pem) {
    auto bio = memory_bio(pem);
    X509Ptr cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
    if (!cert) throw_openssl_error("not a PEM certificate");
    return cert;
}

std::vector<X509Ptr> read_certificates(const std::string& pem) {
    auto bio = memory_bio(pem);
    std::vector<X509Ptr> out;
    while (X509* cert = PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr)) out.emplace_back(cert);
    ERR_clear_error();  // the end of the text reads as an error
    if (out.empty()) throw_openssl_error("not a PEM certificate");
    return out;
}

PKeyPtr read_private_key(const std::string& pem) {
    auto bio = memory_bio(pem);
    PKeyPtr key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
    if (!key) throw_openssl_error("not a PEM private key");
    return key;
}

std::string certificate_pem(X509* certificate) {
    BioPtr bio(BIO_new(BIO_s_mem()));
    if (!bio || PEM_write_bio_X509(bio.get(), certificate) != 1) throw_openssl_error("cannot write PEM");
    return bio_text(bio.get());
}

std::string private_key_pem(EVP_PKEY* key) {
    BioPtr bio(BIO_new(BIO_s_mem()));
    if (!bio || PEM_write_bio_PrivateKey(bio.get(), key, nullptr, nullptr, 0, nullptr, nullptr) != 1)
        throw_openssl_error("cannot write PEM");
    return bio_text(bio.get());
}

std::string certificate_der(X509* certificate) {
    unsigned char* der = nullptr;
    const int len = i2d_X509(certificate, &der);
    if (len <= 0) throw_openssl_error("cannot encode the certificate");
    std::string out(reinterpret_cast<const char*>(der), static_cast<std::size_t>(len));
    OPENSSL_free(der);
    return out;
}

std::string certificate_fingerprint(const std::string& pem) {
    X509Ptr cert = read_certificate(pem);
    std::string fp = native::certificate_fingerprint(cert.get());
    if (fp.empty()) throw_openssl_error("cannot encode the certificate");
    return fp;
}

PKeyPtr new_ec_key() {
    PKeyPtr key(EVP_EC_gen("P-256"));
    if (!key) throw_openssl_error("cannot generate an EC P-256 key");
    return key;
}

X509Ptr new_certificate(EVP_PKEY* key, std::chrono::system_clock::time_point not_before,
                        std::chrono::seconds lifetime) {
    X509Ptr cert(X509_new());
    if (!cert) throw_openssl_error("cannot allocate a certificate");
    if (X509_set_version(cert.get(), X509_VERSION_3) != 1) throw_openssl_error("cannot set the certificate version");
    // A random positive 127-bit serial, so two certificates never share one.
    unsigned char serial[16];
    if (RAND_bytes(serial, sizeof serial) != 1) throw_openssl_error("no random bytes");
    serial[0] &= 0x7f;
    BIGNUM* bn = BN_bin2bn(serial, sizeof serial, nullptr);
    if (!bn || !BN_to_ASN1_INTEGER(bn, X509_get_serialNumber(cert.get()))) {
        BN_free(bn);
        throw_openssl_error("cannot set the serial number");
    }
    BN_free(bn);
    const time_t start = std::chrono::system_clock::to_time_t(not_before);
    if (!ASN1_TIME_adj(X509_getm_notBefore(cert.get()), start, 0, 0) ||
        !ASN1_TIME_adj(X509_getm_notAfter(cert.get()), start, 0, static_cast<long>(lifetime.count())))
        throw_openssl_error("cannot set the validity");
    if (X509_set_pubkey(cert.get(), key) != 1) throw_openssl_error("cannot set the public key");
    return cert;
}

void add_extension(X509* certificate, X509* issuer, int nid, const std::string& value) {
    X509V3_CTX ctx;
    X509V3_set_ctx_nodb(&ctx);
    X509V3_set_ctx(&ctx, issuer, certificate, nullptr, nullptr, 0);
    ExtPtr ext(X509V3_EXT_conf_nid(nullptr, &ctx, nid, value.c_str()));
    if (!ext || X509_add_ext(certificate, ext.get(), -1) != 1)
        throw_openssl_error("cannot add the extension " + value);
}

std::chrono::system_clock::time_point not_after(X509* certificate) {
    struct tm tm {};
    if (ASN1_TIME_to_tm(X509_get0_notAfter(certificate), &tm) != 1) throw_openssl_error("unreadable notAfter");
    return std::chrono::system_clock::from_time_t(timegm(&tm));
}

}  // namespace umf::provider
