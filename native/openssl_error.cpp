#include "native/openssl_error.hpp"

#include <openssl/err.h>

namespace umf::native {

std::string take_openssl_error() {
    std::string detail;
    if (unsigned long e = ERR_get_error(); e != 0) {
        char buf[256];
        ERR_error_string_n(e, buf, sizeof buf);
        detail = std::string(": ") + buf;
    }
    ERR_clear_error();
    return detail;
}

}  // namespace umf::native
