// Pairing: the token a requester proves itself with, and the URL (shown as a
// QR code) that carries it with the certificate's fingerprint. docs/PROTOCOL.md,
// "Pairing".
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "provider/common/base64url.hpp"
#include "provider/common/secret_compare.hpp"

namespace umf::provider {

inline constexpr const char* kTokenFile = "pairing-token";
inline constexpr std::size_t kTokenRandomBytes = 24;  // 192 bits, 32 base64url characters

// kTokenRandomBytes from the operating system's generator, base64url.
std::string make_token();

// The token kept in `dir`: made and saved (0600) when missing, empty or
// malformed, or when `rotate` is set. Throws ConfigError.
std::string load_or_create_token(const std::filesystem::path& dir, bool rotate = false);

// https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT[&n=NAME.local]; an IPv6 host
// goes in brackets.
std::string pairing_url(const std::string& host, unsigned short port, const std::string& token,
                        const std::string& fingerprint, const std::string& local_name = {});

}  // namespace umf::provider
