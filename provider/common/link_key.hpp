// The key of a download or upload link: "/dl/<key>" for what a grab resolved
// (content/download_table.hpp), "/up/<key>" for what a put may send
// (put/upload_table.hpp). 128 random bits, so links cannot be guessed; a
// request's path is only ever a key into those tables, never a path on the
// file system.
#pragma once

#include <string>

namespace umf::provider {

// 22 base64url characters of 128 random bits (OpenSSL's generator). Throws
// std::runtime_error when the generator fails.
std::string random_link_key();

}  // namespace umf::provider
