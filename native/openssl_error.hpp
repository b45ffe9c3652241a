// The error OpenSSL queued last, for a message: what the provider and the
// requester add to their own words when an OpenSSL call fails.
#pragma once

#include <string>

namespace umf::native {

// ": " and OpenSSL's text of the first queued error, or "" when none is
// queued; the queue is cleared either way.
std::string take_openssl_error();

}  // namespace umf::native
