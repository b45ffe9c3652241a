// A TLS certificate's fingerprint as pairing uses it: the SHA-256 of its DER
// encoding, 64 lowercase hex digits. The provider puts its own in the
// pairing URL; the requester trusts the provider whose certificate has it.
#pragma once

#include <cstddef>
#include <string>

struct x509_st;

namespace umf::native {

// SHA-256 of `size` DER bytes as hex; empty when OpenSSL cannot hash.
std::string der_fingerprint(const unsigned char* der, std::size_t size);

// The fingerprint of a certificate; empty for none or one that cannot be
// encoded.
std::string certificate_fingerprint(x509_st* certificate);

}  // namespace umf::native
