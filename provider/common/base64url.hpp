// base64url without padding (RFC 4648, section 5): the alphabet of every
// secret the provider hands out in a URL (the pairing token, one-time links).
#pragma once

#include <cstddef>
#include <string>

namespace umf::provider {

std::string base64url(const unsigned char* data, std::size_t size);

}  // namespace umf::provider
