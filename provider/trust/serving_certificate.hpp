// The certificate the provider serves: issued by the screen's root for the
// host's .local name and its current addresses, for at most 397 days (the
// most any browser accepts), and issued again before it ends or when the
// addresses change.
#pragma once

#include <chrono>
#include <string>

#include "provider/trust/root_authority.hpp"
#include "provider/trust/serving_names.hpp"

namespace umf::provider {

struct ServingCertificate {
    std::string certificate_pem;  // the serving certificate alone
    std::string private_key_pem;
};

inline constexpr std::chrono::seconds kServingLifetime = std::chrono::hours(24 * 397);
// Issued again when less than this is left.
inline constexpr std::chrono::seconds kServingRenewBefore = std::chrono::hours(24 * 30);

// A new key and a certificate for `names` (subjectAltName: every DNS name
// and address; CN the first DNS name), signed by `root`, valid from an hour
// before `now` for kServingLifetime: CA:FALSE, digitalSignature, serverAuth.
// Throws TlsIdentityError.
ServingCertificate issue_serving_certificate(const RootAuthority& root, const ServingNames& names,
                                             std::chrono::system_clock::time_point now);

// Why `serving` cannot be served as it is at `now` for `names`, empty when
// it can: it is not signed by `root`, its key is not its own, it ends within
// kServingRenewBefore, or it does not name every DNS name and address.
std::string reason_to_issue_again(const ServingCertificate& serving, const RootAuthority& root,
                                  const ServingNames& names, std::chrono::system_clock::time_point now);

}  // namespace umf::provider
