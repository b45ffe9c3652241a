// The screen's root and the certificate it issues (provider/trust/): what a
// phone that installs the root will and will not trust, when the serving
// certificate is issued again, the pin requesters check, older pairings,
// the exported forms, and a running server that picks up a new certificate.
#include <gtest/gtest.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>
#include <sys/stat.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "native/certificate_fingerprint.hpp"
#include "native/certificate_pin.hpp"
#include "provider/common/config_dir.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/certificate_keeper.hpp"
#include "provider/trust/openssl_objects.hpp"
#include "provider/trust/root_export.hpp"
#include "provider/trust/serving_certificate.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "tests/support/pinned_client.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using namespace umf::provider;
using umf::test::TempDir;
using Clock = std::chrono::system_clock;
namespace fs = std::filesystem;

const ServingNames kNames = serving_names("desk-7.local", {"192.168.1.20", "10.0.0.5", "fd00::20", "203.0.113.9"});

// OpenSSL's verdict on `leaf` with `root` as the one trust anchor, for a
// host name (`host`) or an address (`ip`), as a browser that installed the
// root decides. X509_V_OK when it verifies.
int verify(const std::string& leaf_pem, const std::string& root_pem, const std::string& host, const std::string& ip) {
    X509Ptr leaf = read_certificate(leaf_pem), root = read_certificate(root_pem);
    std::unique_ptr<X509_STORE, OpenSslFree<X509_STORE, X509_STORE_free>> store(X509_STORE_new());
    X509_STORE_add_cert(store.get(), root.get());
    std::unique_ptr<X509_STORE_CTX, OpenSslFree<X509_STORE_CTX, X509_STORE_CTX_free>> ctx(X509_STORE_CTX_new());
    X509_STORE_CTX_init(ctx.get(), store.get(), leaf.get(), nullptr);
    X509_VERIFY_PARAM* param = X509_STORE_CTX_get0_param(ctx.get());
    X509_VERIFY_PARAM_set_purpose(param, X509_PURPOSE_SSL_SERVER);
    if (!host.empty()) X509_VERIFY_PARAM_set1_host(param, host.c_str(), host.size());
    if (!ip.empty()) X509_VERIFY_PARAM_set1_ip_asc(param, ip.c_str());
    X509_verify_cert(ctx.get());
    return X509_STORE_CTX_get_error(ctx.get());
}

// A leaf for `san` signed by the root's key, as a thief of the root would make one.
std::string forged_leaf(const RootAuthority& root, const std::string& san) {
    X509Ptr issuer = read_certificate(root.certificate_pem);
    PKeyPtr issuer_key = read_private_key(root.private_key_pem);
    PKeyPtr key = new_ec_key();
    X509Ptr cert = new_certificate(key.get(), Clock::now() - std::chrono::hours(1), std::chrono::hours(24));
    X509_set_issuer_name(cert.get(), X509_get_subject_name(issuer.get()));
    add_extension(cert.get(), issuer.get(), NID_ext_key_usage, "serverAuth");
    add_extension(cert.get(), issuer.get(), NID_subject_alt_name, san);
    X509_sign(cert.get(), issuer_key.get(), EVP_sha256());
    return certificate_pem(cert.get());
}

TEST(ScreenRoot, NamesOnlyPrivateAddressesAndLocalNames) {
    EXPECT_EQ(kNames.dns, (std::vector<std::string>{"desk-7.local", "localhost"}));
    EXPECT_EQ(kNames.addresses, (std::vector<std::string>{"10.0.0.5", "127.0.0.1", "192.168.1.20", "::1", "fd00::20"}));
    EXPECT_EQ(kNames.not_covered, std::vector<std::string>{"203.0.113.9"});
    for (const char* a : {"172.16.0.1", "172.31.255.255", "169.254.3.4", "127.9.9.9", "fc12::1"})
        EXPECT_TRUE(address_may_be_vouched(a)) << a;
    for (const char* a : {"172.32.0.1", "8.8.8.8", "2001:db8::1", "fe80::1", "100.64.0.1", "not an address"})
        EXPECT_FALSE(address_may_be_vouched(a)) << a;
    EXPECT_EQ(local_name_for("Desk_7.example.org"), "desk-7.local");
    EXPECT_EQ(local_name_for("localhost"), "");
    EXPECT_EQ(local_name_for("--"), "");
}

TEST(ScreenRoot, ServingCertificateVerifiesForEveryNameAndAddress) {
    const RootAuthority root = create_root_authority("desk-7.local");
    const ServingCertificate serving = issue_serving_certificate(root, kNames, Clock::now());
    for (const auto& d : kNames.dns) EXPECT_EQ(verify(serving.certificate_pem, root.certificate_pem, d, ""), X509_V_OK) << d;
    for (const auto& a : kNames.addresses)
        EXPECT_EQ(verify(serving.certificate_pem, root.certificate_pem, "", a), X509_V_OK) << a;
    // Not named: refused by the name check, not by the constraints.
    EXPECT_EQ(verify(serving.certificate_pem, root.certificate_pem, "other.local", ""), X509_V_ERR_HOSTNAME_MISMATCH);
    EXPECT_EQ(verify(serving.certificate_pem, root.certificate_pem, "", "203.0.113.9"), X509_V_ERR_IP_ADDRESS_MISMATCH);
    // Another screen's root vouches for nothing of this one's.
    const RootAuthority other = create_root_authority("desk-8.local");
    EXPECT_NE(verify(serving.certificate_pem, other.certificate_pem, "desk-7.local", ""), X509_V_OK);

    X509Ptr leaf = read_certificate(serving.certificate_pem);
    const auto lifetime = not_after(leaf.get()) - Clock::now();
    EXPECT_LE(lifetime, std::chrono::hours(24 * 397));
    EXPECT_GT(lifetime, std::chrono::hours(24 * 396));
    EXPECT_EQ(X509_check_ca(leaf.get()), 0);
    EXPECT_NE(X509_get_extended_key_usage(leaf.get()) & XKU_SSL_SERVER, 0u);
    EXPECT_EQ(EVP_PKEY_get_base_id(X509_get0_pubkey(leaf.get())), EVP_PKEY_EC);
    EXPECT_EQ(X509_get_signature_nid(leaf.get()), NID_ecdsa_with_SHA256);
}

TEST(ScreenRoot, AStolenRootCannotVouchForAPublicSite) {
    const RootAuthority root = create_root_authority("desk-7.local");
    X509Ptr cert = read_certificate(root.certificate_pem);
    EXPECT_EQ(X509_check_ca(cert.get()), 1);
    EXPECT_NE(X509_get_ext_by_NID(cert.get(), NID_name_constraints, -1), -1);
    EXPECT_EQ(verify(forged_leaf(root, "DNS:bank.example.com"), root.certificate_pem, "bank.example.com", ""),
              X509_V_ERR_PERMITTED_VIOLATION);
    EXPECT_EQ(verify(forged_leaf(root, "IP:8.8.8.8"), root.certificate_pem, "", "8.8.8.8"),
              X509_V_ERR_PERMITTED_VIOLATION);
    EXPECT_EQ(verify(forged_leaf(root, "IP:2001:db8::1"), root.certificate_pem, "", "2001:db8::1"),
              X509_V_ERR_PERMITTED_VIOLATION);
    // A private name hidden among public ones does not help either.
    EXPECT_EQ(verify(forged_leaf(root, "DNS:desk-7.local,DNS:mail.example.org"), root.certificate_pem, "desk-7.local", ""),
              X509_V_ERR_PERMITTED_VIOLATION);
    EXPECT_EQ(verify(forged_leaf(root, "DNS:printer.local,IP:192.168.7.7"), root.certificate_pem, "printer.local", ""),
              X509_V_OK);
}

TEST(ScreenRoot, IssuedAgainOnlyWhenItNoLongerFits) {
    const RootAuthority root = create_root_authority("desk-7.local");
    const auto now = Clock::now();
    const ServingCertificate serving = issue_serving_certificate(root, kNames, now);
    EXPECT_EQ(reason_to_issue_again(serving, root, kNames, now), "");
    // An address that went away leaves the certificate as it is.
    EXPECT_EQ(reason_to_issue_again(serving, root, serving_names("desk-7.local", {"10.0.0.5"}), now), "");
    EXPECT_EQ(reason_to_issue_again(serving, root, serving_names("desk-7.local", {"10.0.0.5", "192.168.44.2"}), now),
              "it does not name 192.168.44.2");
    EXPECT_EQ(reason_to_issue_again(serving, root, serving_names("desk-9.local", {}), now), "it does not name desk-9.local");
    EXPECT_EQ(reason_to_issue_again(serving, root, kNames, now + std::chrono::hours(24 * 368)), "it ends within 30 days");
    EXPECT_EQ(reason_to_issue_again(serving, create_root_authority("x.local"), kNames, now), "another root issued it");
    const ServingCertificate other = issue_serving_certificate(root, kNames, now);
    EXPECT_EQ(reason_to_issue_again({serving.certificate_pem, other.private_key_pem}, root, kNames, now),
              "its key is not its own");
    EXPECT_NE(reason_to_issue_again({"garbage", serving.private_key_pem}, root, kNames, now), "");
}

TEST(ScreenRoot, KeptInTheConfigurationDirectoryAndIssuedFromIt) {
    TempDir dir;
    const auto now = Clock::now();
    const LoadedIdentity first = load_or_issue_tls_identity(dir.path, kNames, now);
    EXPECT_EQ(first.issued_because, "there was none");
    for (const char* name : {kRootCertificateFile, kRootKeyFile, kServingCertificateFile, kServingKeyFile}) {
        struct stat st {};
        ASSERT_EQ(stat((dir.path / name).c_str(), &st), 0) << name;
        EXPECT_EQ(st.st_mode & 0777, 0600u) << name;
    }
    const LoadedIdentity again = load_or_issue_tls_identity(dir.path, kNames, now);
    EXPECT_EQ(again.issued_because, "");
    EXPECT_EQ(again.identity.certificate_pem, first.identity.certificate_pem);
    // A new address: a new serving certificate, the same root and so the same pin.
    const LoadedIdentity moved =
        load_or_issue_tls_identity(dir.path, serving_names("desk-7.local", {"192.168.77.3"}), now);
    EXPECT_EQ(moved.issued_because, "it does not name 192.168.77.3");
    EXPECT_EQ(moved.identity.fingerprint, first.identity.fingerprint);
    EXPECT_NE(moved.identity.private_key_pem, first.identity.private_key_pem);
    // Half a serving certificate is simply issued again; half a root is an error.
    fs::remove(dir.path / kServingKeyFile);
    EXPECT_NE(load_or_issue_tls_identity(dir.path, kNames, now).issued_because, "");
    fs::remove(dir.path / kRootKeyFile);
    EXPECT_THROW(load_or_issue_tls_identity(dir.path, kNames, now), TlsIdentityError);
    // Rotating the root: a new pin.
    remove_root(dir.path);
    EXPECT_NE(load_or_issue_tls_identity(dir.path, kNames, now).identity.fingerprint, first.identity.fingerprint);
}

// The chain as a requester receives it, and the pin check it runs.
bool pinned(const TlsIdentity& identity, const std::string& fingerprint) {
    const std::vector<X509Ptr> certs = read_certificates(identity.certificate_pem);
    STACK_OF(X509)* chain = sk_X509_new_null();
    for (const auto& c : certs) sk_X509_push(chain, c.get());
    const bool ok = umf::native::chain_satisfies_pin(certs.front().get(), chain, fingerprint);
    sk_X509_free(chain);
    return ok;
}

TEST(ScreenRoot, RequestersPinTheRootNotTheServingCertificate) {
    TempDir dir;
    const TlsIdentity identity = load_or_issue_tls_identity(dir.path, kNames, Clock::now()).identity;
    EXPECT_TRUE(pinned(identity, identity.fingerprint));
    EXPECT_TRUE(pinned(identity, certificate_fingerprint(identity.certificate_pem)));  // the leaf itself
    EXPECT_FALSE(pinned(identity, std::string(64, 'a')));
    // Another screen that copies this root's certificate into its chain does not pass:
    // its serving certificate was not signed by the pinned key.
    const TlsIdentity other = create_tls_identity();
    TlsIdentity impostor = other;
    impostor.certificate_pem += *read_small_file(dir.path / kRootCertificateFile);
    EXPECT_FALSE(pinned(impostor, identity.fingerprint));
    // An expired serving certificate fails the pin even from the right root.
    const RootAuthority root = load_or_create_root(dir.path);
    const ServingCertificate old = issue_serving_certificate(root, kNames, Clock::now() - std::chrono::hours(24 * 400));
    EXPECT_FALSE(pinned({old.certificate_pem + root.certificate_pem, old.private_key_pem, root.fingerprint},
                        root.fingerprint));
}

TEST(ScreenRoot, PairingsFromBeforeRootsKeepWorking) {
    TempDir dir;
    // A directory as providers made it before roots: a self-signed certificate and its key.
    PKeyPtr key = new_ec_key();
    X509Ptr legacy = new_certificate(key.get(), Clock::now() - std::chrono::hours(24), std::chrono::hours(24 * 3650));
    X509_NAME_add_entry_by_txt(X509_get_subject_name(legacy.get()), "CN", MBSTRING_UTF8,
                               reinterpret_cast<const unsigned char*>("umf-provider"), -1, -1, 0);
    X509_set_issuer_name(legacy.get(), X509_get_subject_name(legacy.get()));
    add_extension(legacy.get(), legacy.get(), NID_basic_constraints, "critical,CA:FALSE");
    add_extension(legacy.get(), legacy.get(), NID_subject_alt_name, "DNS:localhost,IP:127.0.0.1");
    X509_sign(legacy.get(), key.get(), EVP_sha256());
    write_private_file(dir.path / kLegacyKeyFile, private_key_pem(key.get()));
    write_private_file(dir.path / kLegacyCertificateFile, certificate_pem(legacy.get()));
    const std::string old_pin = umf::native::certificate_fingerprint(legacy.get());

    const TlsIdentity identity = load_or_issue_tls_identity(dir.path, kNames, Clock::now()).identity;
    EXPECT_NE(identity.fingerprint, old_pin);
    EXPECT_TRUE(pinned(identity, old_pin));       // the URL paired before
    EXPECT_TRUE(pinned(identity, identity.fingerprint));  // a new pairing
    X509Ptr root = read_certificate(*read_small_file(dir.path / kRootCertificateFile));
    EXPECT_EQ(EVP_PKEY_eq(X509_get0_pubkey(root.get()), key.get()), 1);
    // --rotate --root ends it.
    remove_root(dir.path);
    EXPECT_FALSE(pinned(load_or_issue_tls_identity(dir.path, kNames, Clock::now()).identity, old_pin));
}

TEST(ScreenRoot, ExportedInTheFormsPhonesInstall) {
    const RootAuthority root = create_root_authority("desk-7.local");
    const std::string der = export_root(root, RootForm::der);
    const unsigned char* p = reinterpret_cast<const unsigned char*>(der.data());
    X509Ptr from_der(d2i_X509(nullptr, &p, static_cast<long>(der.size())));
    ASSERT_TRUE(from_der);
    EXPECT_EQ(umf::native::certificate_fingerprint(from_der.get()), root.fingerprint);
    EXPECT_EQ(certificate_fingerprint(export_root(root, RootForm::pem)), root.fingerprint);
    EXPECT_EQ(export_root(root, RootForm::pem).find("PRIVATE KEY"), std::string::npos);

    const std::string profile = export_root(root, RootForm::mobileconfig);
    EXPECT_EQ(profile, export_root(root, RootForm::mobileconfig));  // the same root, the same profile
    EXPECT_NE(profile.find("<string>com.apple.security.root</string>"), std::string::npos);
    EXPECT_NE(profile.find("<string>Configuration</string>"), std::string::npos);
    EXPECT_NE(profile.find("umf screen root (desk-7.local)"), std::string::npos);
    // The <data> holds the DER, base64 in lines.
    const auto begin = profile.find("<data>") + 6, end = profile.find("</data>");
    std::string b64;
    for (char c : profile.substr(begin, end - begin))
        if (!std::isspace(static_cast<unsigned char>(c))) b64 += c;
    std::string decoded(b64.size(), '\0');
    const int n = EVP_DecodeBlock(reinterpret_cast<unsigned char*>(decoded.data()),
                                  reinterpret_cast<const unsigned char*>(b64.data()), static_cast<int>(b64.size()));
    ASSERT_GT(n, 0);
    decoded.resize(static_cast<std::size_t>(n) - std::count(b64.end() - 2, b64.end(), '='));
    EXPECT_EQ(decoded, der);
    EXPECT_EQ(fingerprint_for_people("0123456789abcdef"), "0123 4567 89AB CDEF");
}

// The serving certificate a TLS client receives from the server now.
std::string served_leaf_pem(unsigned short port, const std::string& pin) {
    boost::asio::io_context io;
    auto tls = umf::test::pinned_client_context(pin);
    boost::asio::ssl::stream<boost::asio::ip::tcp::socket> stream(io, tls);
    stream.next_layer().connect({boost::asio::ip::make_address("127.0.0.1"), port});
    stream.handshake(boost::asio::ssl::stream_base::client);
    X509* peer = SSL_get1_peer_certificate(stream.native_handle());
    std::string pem = certificate_pem(peer);
    X509_free(peer);
    boost::system::error_code ec;
    stream.shutdown(ec);
    return pem;
}

TEST(ScreenRoot, ARunningServerServesTheCertificateIssuedAgain) {
    TempDir dir;
    const TlsIdentity identity = load_or_issue_tls_identity(dir.path, kNames, Clock::now()).identity;
    auto service = std::make_shared<const Service>(default_service_config(), std::string(32, 't'));
    const auto server = make_server(service, identity);
    server->start();
    const std::string before = served_leaf_pem(server->port(), identity.fingerprint);
    EXPECT_EQ(before, certificate_pem(read_certificate(identity.certificate_pem).get()));

    // The machine gets another address: the keeper issues again and the server serves it.
    std::atomic<bool> moved{false};
    std::atomic<int> issued{0};
    CertificateKeeper::Settings settings;
    settings.config_dir = dir.path;
    settings.interval = std::chrono::milliseconds(50);
    settings.names = [&] { return moved ? serving_names("desk-7.local", {"192.168.1.20", "10.44.0.9"}) : kNames; };
    settings.issued = [&](const TlsIdentity& now, const std::string&) {
        server->replace_identity(now);
        ++issued;
    };
    {
        CertificateKeeper keeper(settings, kNames);
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        EXPECT_EQ(issued, 0);  // nothing changed: nothing issued
        moved = true;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (issued == 0 && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        EXPECT_EQ(issued, 1);
    }
    const std::string after = served_leaf_pem(server->port(), identity.fingerprint);  // the old pin still holds
    EXPECT_NE(after, before);
    X509Ptr leaf = read_certificate(after);
    EXPECT_EQ(X509_check_ip_asc(leaf.get(), "10.44.0.9", 0), 1);
    server->stop();
}

}  // namespace
