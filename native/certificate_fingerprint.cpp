#include "native/certificate_fingerprint.hpp"

#include <openssl/evp.h>
#include <openssl/x509.h>

#include "native/sha256.hpp"

namespace umf::native {

std::string der_fingerprint(const unsigned char* der, std::size_t size) {
    unsigned char md[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    if (EVP_Digest(der, size, md, &len, EVP_sha256(), nullptr) != 1) return {};
    return to_hex(md, len);
}

std::string certificate_fingerprint(X509* certificate) {
    if (!certificate) return {};
    unsigned char* der = nullptr;
    const int len = i2d_X509(certificate, &der);
    if (len <= 0) return {};
    std::string fp = der_fingerprint(der, static_cast<std::size_t>(len));
    OPENSSL_free(der);
    return fp;
}

}  // namespace umf::native
