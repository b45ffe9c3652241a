#include "provider/common/secret_compare.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>

namespace umf::provider {

bool tokens_equal(std::string_view a, std::string_view b) {
    unsigned char da[EVP_MAX_MD_SIZE], db[EVP_MAX_MD_SIZE];
    unsigned int la = 0, lb = 0;
    if (EVP_Digest(a.data(), a.size(), da, &la, EVP_sha256(), nullptr) != 1 ||
        EVP_Digest(b.data(), b.size(), db, &lb, EVP_sha256(), nullptr) != 1 || la != lb)
        return false;
    return CRYPTO_memcmp(da, db, la) == 0 && a.size() == b.size();
}

}  // namespace umf::provider
