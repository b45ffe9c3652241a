// Standard base64 (RFC 4648, section 4) back to bytes: what the extension
// sends an image's bytes as, and the public key in its manifest.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace umf::provider {

// nullopt on any character outside the alphabet, or padding before the end.
std::optional<std::string> base64_decode(std::string_view text);

}  // namespace umf::provider
