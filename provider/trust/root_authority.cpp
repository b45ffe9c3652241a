#include "provider/trust/root_authority.hpp"

#include <openssl/x509.h>

#include "provider/trust/tls_identity.hpp"

namespace umf::provider {

// RFC 5280 4.2.1.10: a DNS constraint "local" permits local and every name
// below it; an IP constraint is an address and its mask.
const char* const kRootNameConstraints =
    "critical,permitted;DNS:local,permitted;DNS:localhost,"
    "permitted;IP:10.0.0.0/255.0.0.0,permitted;IP:172.16.0.0/255.240.0.0,"
    "permitted;IP:192.168.0.0/255.255.0.0,permitted;IP:169.254.0.0/255.255.0.0,"
    "permitted;IP:127.0.0.0/255.0.0.0,permitted;IP:fc00::/fe00::,"
    "permitted;IP:::1/ffff:ffff:ffff:ffff:ffff:ffff:ffff:ffff";

RootAuthority create_root_authority(const std::string& screen_name, EVP_PKEY* key) {
    PKeyPtr made;
    if (!key) {
        made = new_ec_key();
        key = made.get();
    }
    const auto now = std::chrono::system_clock::now();
    X509Ptr cert = new_certificate(key, now - std::chrono::hours(1), kRootLifetime);
    X509_NAME* name = X509_get_subject_name(cert.get());
    const std::string common_name = "umf screen root" + (screen_name.empty() ? "" : " (" + screen_name + ")");
    if (X509_NAME_add_entry_by_txt(name, "O", MBSTRING_UTF8, reinterpret_cast<const unsigned char*>("umf"), -1, -1,
                                   0) != 1 ||
        X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_UTF8,
                                   reinterpret_cast<const unsigned char*>(common_name.c_str()), -1, -1, 0) != 1 ||
        X509_set_issuer_name(cert.get(), name) != 1)
        throw_openssl_error("cannot set the root's name");
    add_extension(cert.get(), cert.get(), NID_basic_constraints, "critical,CA:TRUE,pathlen:0");
    add_extension(cert.get(), cert.get(), NID_key_usage, "critical,keyCertSign,cRLSign");
    add_extension(cert.get(), cert.get(), NID_subject_key_identifier, "hash");
    add_extension(cert.get(), cert.get(), NID_name_constraints, kRootNameConstraints);
    if (X509_sign(cert.get(), key, EVP_sha256()) <= 0) throw_openssl_error("cannot sign the root");

    RootAuthority root;
    root.certificate_pem = certificate_pem(cert.get());
    root.private_key_pem = private_key_pem(key);
    root.fingerprint = certificate_fingerprint(root.certificate_pem);
    return root;
}

RootAuthority checked_root_authority(const std::string& certificate_pem_text, const std::string& private_key_pem_text) {
    X509Ptr cert = read_certificate(certificate_pem_text);
    PKeyPtr key = read_private_key(private_key_pem_text);
    if (X509_check_private_key(cert.get(), key.get()) != 1) throw_openssl_error("the key does not belong to the root");
    if (X509_check_ca(cert.get()) == 0) throw TlsIdentityError("the root is not a certificate authority");
    if (X509_check_issued(cert.get(), cert.get()) != X509_V_OK) throw TlsIdentityError("the root is not self-signed");
    return {certificate_pem_text, private_key_pem_text, certificate_fingerprint(certificate_pem_text)};
}

}  // namespace umf::provider
