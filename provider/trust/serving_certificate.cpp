#include "provider/trust/serving_certificate.hpp"

#include <openssl/x509v3.h>

#include <algorithm>

#include "provider/trust/tls_identity.hpp"

namespace umf::provider {

namespace {

std::string subject_alt_names(const ServingNames& names) {
    std::string san;
    for (const auto& d : names.dns) san += (san.empty() ? "DNS:" : ",DNS:") + d;
    for (const auto& a : names.addresses) san += (san.empty() ? "IP:" : ",IP:") + a;
    return san;
}

}  // namespace

ServingCertificate issue_serving_certificate(const RootAuthority& root, const ServingNames& names,
                                             std::chrono::system_clock::time_point now) {
    if (names.dns.empty() && names.addresses.empty()) throw TlsIdentityError("no name to issue a certificate for");
    X509Ptr issuer = read_certificate(root.certificate_pem);
    PKeyPtr issuer_key = read_private_key(root.private_key_pem);
    PKeyPtr key = new_ec_key();
    X509Ptr cert = new_certificate(key.get(), now - std::chrono::hours(1), kServingLifetime);
    const std::string common_name = names.dns.empty() ? names.addresses.front() : names.dns.front();
    X509_NAME* subject = X509_get_subject_name(cert.get());
    if (X509_NAME_add_entry_by_txt(subject, "CN", MBSTRING_UTF8,
                                   reinterpret_cast<const unsigned char*>(common_name.c_str()), -1, -1, 0) != 1 ||
        X509_set_issuer_name(cert.get(), X509_get_subject_name(issuer.get())) != 1)
        throw_openssl_error("cannot set the certificate's names");
    add_extension(cert.get(), issuer.get(), NID_basic_constraints, "critical,CA:FALSE");
    add_extension(cert.get(), issuer.get(), NID_key_usage, "critical,digitalSignature");
    add_extension(cert.get(), issuer.get(), NID_ext_key_usage, "serverAuth");
    add_extension(cert.get(), issuer.get(), NID_subject_key_identifier, "hash");
    add_extension(cert.get(), issuer.get(), NID_authority_key_identifier, "keyid:always");
    add_extension(cert.get(), issuer.get(), NID_subject_alt_name, subject_alt_names(names));
    if (X509_sign(cert.get(), issuer_key.get(), EVP_sha256()) <= 0) throw_openssl_error("cannot sign the certificate");
    return {certificate_pem(cert.get()), private_key_pem(key.get())};
}

std::string reason_to_issue_again(const ServingCertificate& serving, const RootAuthority& root,
                                  const ServingNames& names, std::chrono::system_clock::time_point now) {
    X509Ptr cert, issuer;
    PKeyPtr key;
    try {
        cert = read_certificate(serving.certificate_pem);
        key = read_private_key(serving.private_key_pem);
        issuer = read_certificate(root.certificate_pem);
    } catch (const TlsIdentityError& e) {
        return std::string("it cannot be read (") + e.what() + ")";
    }
    if (X509_check_private_key(cert.get(), key.get()) != 1) return "its key is not its own";
    if (X509_verify(cert.get(), X509_get0_pubkey(issuer.get())) != 1) return "another root issued it";
    if (not_after(cert.get()) - now < kServingRenewBefore) return "it ends within 30 days";
    for (const auto& d : names.dns)
        if (X509_check_host(cert.get(), d.c_str(), d.size(), X509_CHECK_FLAG_NO_PARTIAL_WILDCARDS, nullptr) != 1)
            return "it does not name " + d;
    for (const auto& a : names.addresses)
        if (X509_check_ip_asc(cert.get(), a.c_str(), 0) != 1) return "it does not name " + a;
    return {};
}

}  // namespace umf::provider
