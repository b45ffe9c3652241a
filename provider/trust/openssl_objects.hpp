// OpenSSL's objects with owners, and its errors as exceptions, for the code
// that makes and reads the provider's certificates.
#pragma once

#include <openssl/bio.h>
#include <openssl/evp.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace umf::provider {

template <class T, void (*Free)(T*)>
struct OpenSslFree {
    void operator()(T* p) const { Free(p); }
};
using PKeyPtr = std::unique_ptr<EVP_PKEY, OpenSslFree<EVP_PKEY, EVP_PKEY_free>>;
using X509Ptr = std::unique_ptr<X509, OpenSslFree<X509, X509_free>>;
using BioPtr = std::unique_ptr<BIO, OpenSslFree<BIO, BIO_free_all>>;

// Throws TlsIdentityError with `what` and the first error OpenSSL has queued
// (the queue is cleared).
[[noreturn]] void throw_openssl_error(const std::string& what);

// PEM in and out. The readers throw TlsIdentityError naming what is wrong.
X509Ptr read_certificate(const std::string& pem);
std::vector<X509Ptr> read_certificates(const std::string& pem);  // every certificate, in order
PKeyPtr read_private_key(const std::string& pem);
std::string certificate_pem(X509* certificate);
std::string private_key_pem(EVP_PKEY* key);
std::string certificate_der(X509* certificate);

// SHA-256 of the first certificate in `pem`, as 64 lowercase hex digits,
// as pairing pins it.
std::string certificate_fingerprint(const std::string& pem);

// A new EC P-256 key pair.
PKeyPtr new_ec_key();

// A new version-3 certificate for `key` with a random positive serial,
// valid from `not_before` for `lifetime`; names and extensions are the
// caller's.
X509Ptr new_certificate(EVP_PKEY* key, std::chrono::system_clock::time_point not_before,
                        std::chrono::seconds lifetime);

// Adds the extension written as in openssl.cnf (for example
// "critical,CA:TRUE"), with `issuer` for the authority key identifier.
void add_extension(X509* certificate, X509* issuer, int nid, const std::string& value);

// notAfter as a point in time.
std::chrono::system_clock::time_point not_after(X509* certificate);

}  // namespace umf::provider
