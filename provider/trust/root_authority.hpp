// The screen's own certificate authority: a root made on first start, kept
// in the configuration directory, that issues the certificate the provider
// serves. Its name constraints permit only .local names, localhost and
// private, link-local and loopback addresses, so a phone that trusts it
// trusts nothing else: a stolen root cannot vouch for a public site.
// Pairing pins it (docs/PROTOCOL.md, "Pairing"); docs/SECURITY.md, "The
// screen's root".
#pragma once

#include <chrono>
#include <string>

#include "provider/trust/openssl_objects.hpp"

namespace umf::provider {

struct RootAuthority {
    std::string certificate_pem;
    std::string private_key_pem;
    std::string fingerprint;  // SHA-256 of the certificate's DER, 64 lowercase hex digits
};

// How long a root lasts. Long: a new root means pairing every phone again.
inline constexpr std::chrono::seconds kRootLifetime = std::chrono::hours(24 * 3650);

// The name constraints in openssl.cnf's syntax (serving_names.cpp keeps
// the same ranges for the addresses it offers).
extern const char* const kRootNameConstraints;

// A root for `key` (a new EC P-256 key when null) named after the screen
// ("umf screen root (HOST)"), valid from an hour ago for kRootLifetime:
// CA:TRUE with no intermediates below it, keyCertSign and cRLSign, the
// name constraints above, SHA-256. Throws TlsIdentityError.
RootAuthority create_root_authority(const std::string& screen_name, EVP_PKEY* key = nullptr);

// Checks that the key belongs to the certificate and that it is a root of
// this kind (CA, self-signed) and fills the fingerprint. Throws
// TlsIdentityError saying which.
RootAuthority checked_root_authority(const std::string& certificate_pem, const std::string& private_key_pem);

}  // namespace umf::provider
