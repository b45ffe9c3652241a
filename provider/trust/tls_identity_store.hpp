// The provider's certificates in its configuration directory: the screen's
// root (root_authority.hpp) and the serving certificate it issued
// (serving_certificate.hpp), each with its key, all files 0600. The root is
// made once and kept, since pairing pins it; the serving certificate is
// issued again whenever it no longer fits. A directory from before roots
// holds a self-signed certificate (provider-cert.pem) whose fingerprint
// older pairing URLs carry: its key becomes the root's key and it is served
// after the root, so those URLs keep working (docs/PROTOCOL.md, "Pairing").
#pragma once

#include <chrono>
#include <filesystem>
#include <string>

#include "provider/trust/root_authority.hpp"
#include "provider/trust/serving_names.hpp"
#include "provider/trust/tls_identity.hpp"

namespace umf::provider {

inline constexpr const char* kRootCertificateFile = "root-cert.pem";
inline constexpr const char* kRootKeyFile = "root-key.pem";
inline constexpr const char* kServingCertificateFile = "serving-cert.pem";
inline constexpr const char* kServingKeyFile = "serving-key.pem";
inline constexpr const char* kLegacyCertificateFile = "provider-cert.pem";
inline constexpr const char* kLegacyKeyFile = "provider-key.pem";

// The root kept in `dir`, made (from the legacy key where there is one) and
// saved when there is none. Half a root, or a key that is not the
// certificate's, is an error rather than replaced, since a new root unpairs
// every requester. Throws TlsIdentityError or ConfigError.
RootAuthority load_or_create_root(const std::filesystem::path& dir);

// Removes the root, the serving certificate and the legacy certificate with
// their keys (`pair --rotate --root`): the next start makes a new root, and
// every requester must pair again. Throws ConfigError.
void remove_root(const std::filesystem::path& dir);

struct LoadedIdentity {
    TlsIdentity identity;
    RootAuthority root;  // the identity's root
    std::string issued_because;  // why the serving certificate was issued now; empty when the kept one serves
};

// The identity to serve for `names` at `now`: the kept serving certificate
// when it still fits, else a new one (saved). Throws as load_or_create_root.
LoadedIdentity load_or_issue_tls_identity(const std::filesystem::path& dir, const ServingNames& names,
                                          std::chrono::system_clock::time_point now);

// load_or_issue_tls_identity for this machine's names, now.
TlsIdentity load_or_create_tls_identity(const std::filesystem::path& dir);

// A new root and a serving certificate from it for this machine's names,
// kept nowhere: another screen, for tests and benchmarks.
TlsIdentity create_tls_identity();

}  // namespace umf::provider
