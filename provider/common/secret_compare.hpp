// Comparing secrets a request presents (the pairing token in a hello, the
// bearer token of a download) with the provider's, without the time taken
// telling an attacker how much of a guess was right.
#pragma once

#include <string_view>

namespace umf::provider {

// True when a and b are equal, in time independent of where they differ
// (both are hashed first, so their lengths do not show either).
bool tokens_equal(std::string_view a, std::string_view b);

}  // namespace umf::provider
