#include "provider/common/screen_name.hpp"

#include <climits>
#include <unistd.h>

namespace umf::provider {

std::string screen_name() {
    char host[HOST_NAME_MAX + 1] = {};
    return ::gethostname(host, sizeof host - 1) == 0 && host[0] ? host : "umf-provider";
}

}  // namespace umf::provider
