#include "provider/trust/root_export.hpp"

#include <openssl/evp.h>

#include <cctype>

namespace umf::provider {

namespace {

std::string base64_lines(const std::string& bytes) {
    std::string out;
    for (std::size_t at = 0; at < bytes.size(); at += 48) {
        const std::size_t n = std::min<std::size_t>(48, bytes.size() - at);
        unsigned char line[65];
        const int len = EVP_EncodeBlock(line, reinterpret_cast<const unsigned char*>(bytes.data()) + at,
                                        static_cast<int>(n));
        out.append(reinterpret_cast<const char*>(line), static_cast<std::size_t>(len));
        out += '\n';
    }
    return out;
}

// A UUID's text made of the fingerprint's digits (version 4 and variant bits
// set), stable for one root.
std::string uuid_from(const std::string& hex, char salt) {
    std::string h = hex.substr(0, 32);
    h[0] = salt;
    h[12] = '4';
    h[16] = "89ab"[std::isdigit(static_cast<unsigned char>(h[16])) ? (h[16] - '0') % 4 : (h[16] - 'a' + 10) % 4];
    for (char& c : h) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return h.substr(0, 8) + "-" + h.substr(8, 4) + "-" + h.substr(12, 4) + "-" + h.substr(16, 4) + "-" + h.substr(20, 12);
}

std::string xml_text(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else out += c;
    }
    return out;
}

std::string root_name(const RootAuthority& root) {
    X509Ptr cert = read_certificate(root.certificate_pem);
    char name[256] = {};
    X509_NAME_get_text_by_NID(X509_get_subject_name(cert.get()), NID_commonName, name, sizeof name);
    return name[0] ? name : "umf screen root";
}

// Apple's configuration profile format: a plist whose one payload is a
// com.apple.security.root holding the certificate's DER.
std::string profile(const RootAuthority& root, const std::string& der) {
    const std::string name = xml_text(root_name(root));
    const std::string id = root.fingerprint.substr(0, 16);
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<!DOCTYPE plist PUBLIC \"-//Apple//DTD PLIST 1.0//EN\" \"http://www.apple.com/DTDs/PropertyList-1.0.dtd\">\n"
           "<plist version=\"1.0\">\n<dict>\n"
           "  <key>PayloadContent</key>\n  <array>\n    <dict>\n"
           "      <key>PayloadCertificateFileName</key>\n      <string>umf-root.cer</string>\n"
           "      <key>PayloadContent</key>\n      <data>\n" + base64_lines(der) + "      </data>\n"
           "      <key>PayloadDescription</key>\n      <string>Lets this device trust the screen it paired with. "
           "The root may only vouch for .local names and private network addresses.</string>\n"
           "      <key>PayloadDisplayName</key>\n      <string>" + name + "</string>\n"
           "      <key>PayloadIdentifier</key>\n      <string>umf.screen-root." + id + ".certificate</string>\n"
           "      <key>PayloadType</key>\n      <string>com.apple.security.root</string>\n"
           "      <key>PayloadUUID</key>\n      <string>" + uuid_from(root.fingerprint, 'a') + "</string>\n"
           "      <key>PayloadVersion</key>\n      <integer>1</integer>\n"
           "    </dict>\n  </array>\n"
           "  <key>PayloadDescription</key>\n  <string>The certificate of the umf screen you paired with.</string>\n"
           "  <key>PayloadDisplayName</key>\n  <string>" + name + "</string>\n"
           "  <key>PayloadIdentifier</key>\n  <string>umf.screen-root." + id + "</string>\n"
           "  <key>PayloadRemovalDisallowed</key>\n  <false/>\n"
           "  <key>PayloadType</key>\n  <string>Configuration</string>\n"
           "  <key>PayloadUUID</key>\n  <string>" + uuid_from(root.fingerprint, 'b') + "</string>\n"
           "  <key>PayloadVersion</key>\n  <integer>1</integer>\n"
           "</dict>\n</plist>\n";
}

}  // namespace

std::string export_root(const RootAuthority& root, RootForm form) {
    X509Ptr cert = read_certificate(root.certificate_pem);
    switch (form) {
        case RootForm::pem: return certificate_pem(cert.get());
        case RootForm::der: return certificate_der(cert.get());
        case RootForm::mobileconfig: return profile(root, certificate_der(cert.get()));
    }
    return {};
}

std::string fingerprint_for_people(const std::string& fingerprint) {
    std::string out;
    for (std::size_t i = 0; i < fingerprint.size(); ++i) {
        if (i > 0 && i % 4 == 0) out += ' ';
        out += static_cast<char>(std::toupper(static_cast<unsigned char>(fingerprint[i])));
    }
    return out;
}

}  // namespace umf::provider
