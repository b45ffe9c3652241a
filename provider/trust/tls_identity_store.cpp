#include "provider/trust/tls_identity_store.hpp"

#include "provider/common/config_dir.hpp"
#include "provider/trust/serving_certificate.hpp"

namespace umf::provider {

namespace {

// Both files of a pair, or neither; one alone is an error naming the other.
std::optional<std::pair<std::string, std::string>> read_pair(const std::filesystem::path& dir, const char* cert_file,
                                                             const char* key_file, const std::string& what) {
    const auto cert_path = dir / cert_file, key_path = dir / key_file;
    auto cert = read_small_file(cert_path);
    auto key = read_small_file(key_path);
    if (!cert && !key) return std::nullopt;
    if (!cert || !key)
        throw TlsIdentityError((cert ? key_path : cert_path).string() + " is missing; remove " +
                               (cert ? cert_path : key_path).string() + " to make a new " + what +
                               " (paired requesters must pair again)");
    return std::make_pair(*cert, *key);
}

RootAuthority root_from_legacy(const std::filesystem::path& dir, const std::string& cert_pem,
                               const std::string& key_pem) {
    try {
        X509Ptr cert = read_certificate(cert_pem);
        PKeyPtr key = read_private_key(key_pem);
        if (X509_check_private_key(cert.get(), key.get()) != 1) throw_openssl_error("the key is not the certificate's");
        return create_root_authority(local_host_name(), key.get());
    } catch (const TlsIdentityError& e) {
        throw TlsIdentityError((dir / kLegacyCertificateFile).string() + ": " + e.what());
    }
}

// The legacy certificate when its key is the root's: served after the root.
std::string legacy_chain_part(const std::filesystem::path& dir, const RootAuthority& root) {
    const auto legacy = read_small_file(dir / kLegacyCertificateFile);
    if (!legacy) return {};
    try {
        X509Ptr cert = read_certificate(*legacy);
        X509Ptr root_cert = read_certificate(root.certificate_pem);
        if (EVP_PKEY_eq(X509_get0_pubkey(cert.get()), X509_get0_pubkey(root_cert.get())) == 1)
            return certificate_pem(cert.get());
    } catch (const TlsIdentityError&) {
    }
    return {};
}

}  // namespace

RootAuthority load_or_create_root(const std::filesystem::path& dir) {
    ensure_config_dir(dir);
    if (auto pair = read_pair(dir, kRootCertificateFile, kRootKeyFile, "root")) {
        try {
            return checked_root_authority(pair->first, pair->second);
        } catch (const TlsIdentityError& e) {
            throw TlsIdentityError((dir / kRootCertificateFile).string() + ": " + e.what());
        }
    }
    const auto legacy = read_pair(dir, kLegacyCertificateFile, kLegacyKeyFile, "identity");
    RootAuthority root = legacy ? root_from_legacy(dir, legacy->first, legacy->second)
                                : create_root_authority(local_host_name());
    // The key first: a certificate without its key would be the worse half.
    write_private_file(dir / kRootKeyFile, root.private_key_pem);
    write_private_file(dir / kRootCertificateFile, root.certificate_pem);
    return root;
}

void remove_root(const std::filesystem::path& dir) {
    for (const char* file : {kServingCertificateFile, kServingKeyFile, kRootCertificateFile, kLegacyCertificateFile,
                             kRootKeyFile, kLegacyKeyFile}) {
        std::error_code ec;
        std::filesystem::remove(dir / file, ec);
        if (ec) throw ConfigError("cannot remove " + (dir / file).string() + ": " + ec.message());
    }
}

LoadedIdentity load_or_issue_tls_identity(const std::filesystem::path& dir, const ServingNames& names,
                                          std::chrono::system_clock::time_point now) {
    const RootAuthority root = load_or_create_root(dir);
    LoadedIdentity loaded;
    loaded.root = root;
    ServingCertificate serving;
    try {
        if (auto kept = read_pair(dir, kServingCertificateFile, kServingKeyFile, "serving certificate"))
            serving = {kept->first, kept->second};
        else
            loaded.issued_because = "there was none";
    } catch (const TlsIdentityError&) {
        // Half a serving certificate: no pairing depends on it.
        loaded.issued_because = "its key or certificate was missing";
    }
    if (loaded.issued_because.empty()) loaded.issued_because = reason_to_issue_again(serving, root, names, now);
    if (!loaded.issued_because.empty()) {
        serving = issue_serving_certificate(root, names, now);
        write_private_file(dir / kServingKeyFile, serving.private_key_pem);
        write_private_file(dir / kServingCertificateFile, serving.certificate_pem);
    }
    loaded.identity.certificate_pem = serving.certificate_pem + root.certificate_pem + legacy_chain_part(dir, root);
    loaded.identity.private_key_pem = serving.private_key_pem;
    loaded.identity.fingerprint = root.fingerprint;
    return loaded;
}

TlsIdentity load_or_create_tls_identity(const std::filesystem::path& dir) {
    return load_or_issue_tls_identity(dir, current_serving_names(), std::chrono::system_clock::now()).identity;
}

TlsIdentity create_tls_identity() {
    const RootAuthority root = create_root_authority(local_host_name());
    const ServingCertificate serving =
        issue_serving_certificate(root, current_serving_names(), std::chrono::system_clock::now());
    return {serving.certificate_pem + root.certificate_pem, serving.private_key_pem, root.fingerprint};
}

}  // namespace umf::provider
