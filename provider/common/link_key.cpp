#include "provider/common/link_key.hpp"

#include <openssl/rand.h>

#include <stdexcept>

#include "provider/common/base64url.hpp"

namespace umf::provider {

std::string random_link_key() {
    unsigned char random[16];
    if (RAND_bytes(random, sizeof random) != 1) throw std::runtime_error("the random generator failed");
    return base64url(random, sizeof random);
}

}  // namespace umf::provider
