// The screen's root in the forms people install it from: PEM (desktops,
// `certutil`, `openssl`), DER (.crt: Android's "CA certificate") and an
// Apple configuration profile (.mobileconfig: iOS and macOS).
#pragma once

#include <string>

#include "provider/trust/root_authority.hpp"

namespace umf::provider {

enum class RootForm { pem, der, mobileconfig };

// The root's certificate (never its key) in `form`. The profile's
// identifiers come from the fingerprint, so exporting again gives the same
// profile and installing it again replaces it. Throws TlsIdentityError.
std::string export_root(const RootAuthority& root, RootForm form);

// "AB12 CD34 ..." : the fingerprint in groups of four, upper case, for a
// person to compare with what the phone shows.
std::string fingerprint_for_people(const std::string& fingerprint);

// The paths where the phone page offers the root (served without a token:
// the root is no secret, every handshake sends it).
inline constexpr const char* kRootDerPath = "/trust/umf-root.crt";
inline constexpr const char* kRootProfilePath = "/trust/umf-root.mobileconfig";

}  // namespace umf::provider
