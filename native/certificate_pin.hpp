// The pin a pairing URL sets (docs/PROTOCOL.md, "Pairing"): the SHA-256 of
// one certificate of the provider's chain. Today that is the screen's root,
// whose key issued the certificate served; before roots it was the served
// certificate itself. Only the pin is trusted: no CA store, no host name
// (the pin names the screen, whatever address it is reached at).
#pragma once

#include <string>

struct x509_st;
struct stack_st_X509;

namespace umf::native {

// True when `leaf` (the certificate the peer served) satisfies the pin
// `fingerprint`: it is the pinned certificate, or the pinned certificate is
// among `chain` (what the peer sent, the leaf included or not) and its key
// signed the leaf, which is valid now.
bool chain_satisfies_pin(x509_st* leaf, stack_st_X509* chain, const std::string& fingerprint);

}  // namespace umf::native
