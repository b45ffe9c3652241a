#include "native/certificate_pin.hpp"

#include <openssl/x509.h>

#include "native/certificate_fingerprint.hpp"

namespace umf::native {

bool chain_satisfies_pin(X509* leaf, STACK_OF(X509)* chain, const std::string& fingerprint) {
    if (!leaf || fingerprint.empty()) return false;
    if (certificate_fingerprint(leaf) == fingerprint) return true;
    // The pinned certificate's key must have signed the leaf; the chain only
    // says which certificate that is, and proves nothing by itself.
    if (X509_cmp_current_time(X509_get0_notBefore(leaf)) >= 0 || X509_cmp_current_time(X509_get0_notAfter(leaf)) <= 0)
        return false;
    for (int i = 0; chain && i < sk_X509_num(chain); ++i) {
        X509* candidate = sk_X509_value(chain, i);
        if (candidate == leaf || certificate_fingerprint(candidate) != fingerprint) continue;
        EVP_PKEY* key = X509_get0_pubkey(candidate);
        if (key && X509_verify(leaf, key) == 1) return true;
    }
    return false;
}

}  // namespace umf::native
