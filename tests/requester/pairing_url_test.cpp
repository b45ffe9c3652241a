// The requester's pure helpers, header-only so they are tested without the
// requester's program: the pairing URL parser, the names a download takes
// when its own is used, and the default download directory.
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>

#include <string>

#include "../../requester/download_dir.hpp"
#include "../../requester/pairing_url.hpp"
#include "io/unique_name.hpp"

namespace {

using umf::io::numbered_name;
using umf::requester::PairingUrl;
using umf::requester::PairingUrlError;
using umf::requester::parse_pairing_url;
using umf::requester::parse_user_dirs_download;

const std::string kToken = "3q2-7wEe9KcFzE1p0xH4aA";  // 22 characters, the shortest allowed
const std::string kFp = "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08";

std::string fragment() { return "#t=" + kToken + "&fp=" + kFp; }

// The message of the PairingUrlError `url` raises, or "" when it parses.
std::string error_of(const std::string& url) {
    try {
        parse_pairing_url(url);
    } catch (const PairingUrlError& e) {
        return e.what();
    }
    return "";
}

TEST(PairingUrl, ParsesTheProvidersForm) {
    const PairingUrl u = parse_pairing_url("https://192.168.1.20:47470/" + fragment());
    EXPECT_EQ(u.host, "192.168.1.20");
    EXPECT_TRUE(u.host_is_ip);
    EXPECT_FALSE(u.host_is_ipv6);
    EXPECT_EQ(u.port, 47470);
    EXPECT_EQ(u.token, kToken);
    EXPECT_EQ(u.fingerprint, kFp);
    EXPECT_EQ(u.authority(), "192.168.1.20:47470");
}

TEST(PairingUrl, HostsByNameAndIpv6) {
    const PairingUrl name = parse_pairing_url("https://desk-1.local:443/" + fragment());
    EXPECT_EQ(name.host, "desk-1.local");
    EXPECT_FALSE(name.host_is_ip);
    const PairingUrl v6 = parse_pairing_url("https://[fe80::1]:8443/" + fragment());
    EXPECT_EQ(v6.host, "fe80::1");
    EXPECT_TRUE(v6.host_is_ipv6);
    EXPECT_TRUE(v6.host_is_ip);
    EXPECT_EQ(v6.authority(), "[fe80::1]:8443");
    EXPECT_EQ(parse_pairing_url("https://[::1]:1/" + fragment()).port, 1);
}

TEST(PairingUrl, ToleratesWhatPastingAndQrAppsDo) {
    // Upper-case scheme, no path, surrounding white space, another order,
    // unknown parameters (a later version may add some), an escaped colon.
    EXPECT_EQ(parse_pairing_url("  HTTPS://h:5#fp=" + kFp + "&x=1&t=" + kToken + "\n").token, kToken);
    std::string colons;
    for (std::size_t i = 0; i < kFp.size(); i += 2) colons += (i ? ":" : "") + kFp.substr(i, 2);
    for (auto& c : colons) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_EQ(parse_pairing_url("https://h:5/#t=" + kToken + "&fp=" + colons).fingerprint, kFp);
    std::string escaped = colons;
    for (std::size_t at; (at = escaped.find(':')) != std::string::npos;) escaped.replace(at, 1, "%3A");
    EXPECT_EQ(parse_pairing_url("https://h:5/#t=" + kToken + "&fp=" + escaped).fingerprint, kFp);
    std::string upper = kFp;
    for (auto& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_EQ(parse_pairing_url("https://h:5/#t=" + kToken + "&fp=" + upper).fingerprint, kFp);
    EXPECT_EQ(parse_pairing_url("https://h/" + fragment()).port, 443);
    EXPECT_EQ(parse_pairing_url("https://h:5/#t=" + std::string(128, 'A') + "&fp=" + kFp).token.size(), 128u);
}

TEST(PairingUrl, RefusesWithAMessageSayingWhat) {
    struct Case {
        std::string url;
        const char* says;
    };
    const Case cases[] = {
        {"", "empty"},
        {"http://h:5/" + fragment(), "https"},
        {"h:5/" + fragment(), "https://"},
        {"https://h:5/", "#t=TOKEN"},
        {"https://h:5/#fp=" + kFp, "no token"},
        {"https://h:5/#t=" + kToken, "no certificate fingerprint"},
        {"https://h:5/#t=" + kToken + "&t=" + kToken + "&fp=" + kFp, "twice"},
        {"https://h:5/#t=short&fp=" + kFp, "22 to 128"},
        {"https://h:5/#t=" + std::string(129, 'A') + "&fp=" + kFp, "22 to 128"},
        {"https://h:5/#t=" + kToken + "+/=&fp=" + kFp, "letters, digits"},
        {"https://h:5/#t=" + kToken + "&fp=" + kFp.substr(2), "64 hex"},
        {"https://h:5/#t=" + kToken + "&fp=" + kFp.substr(1) + "g", "64 hex"},
        {"https://h:5/#t=" + kToken + "&fp=9:f86" + kFp.substr(4), "64 hex"},
        {"https://h:5/#t=" + kToken + "&fp=%zz", "%-escape"},
        {"https://h:0/" + fragment(), "1..65535"},
        {"https://h:65536/" + fragment(), "1..65535"},
        {"https://h:http/" + fragment(), "not a number"},
        {"https://h:/" + fragment(), "no port"},
        {"https://:5/" + fragment(), "no host"},
        {"https://fe80::1:5/" + fragment(), "brackets"},
        {"https://[fe80::g]:5/" + fragment(), "not an IPv6"},
        {"https://[::1/" + fragment(), "']'"},
        {"https://300.1.1.1:5/" + fragment(), "not an IPv4"},
        {"https://bad_host:5/" + fragment(), "not a host name"},
        {"https://-bad:5/" + fragment(), "not a host name"},
        {"https://user@h:5/" + fragment(), "user name"},
        {"https://h:5/ws" + fragment(), "no path"},
        {"https://h:5/ " + fragment(), "spaces"},
    };
    for (const auto& c : cases) {
        const std::string message = error_of(c.url);
        EXPECT_NE(message.find(c.says), std::string::npos) << c.url << " -> '" << message << "'";
    }
}

TEST(PairingUrl, AcceptsWhatTheProviderPrints) {
    // provider/server/pairing.cpp's pairing_url(): bracketed IPv6 and the
    // 32-character tokens make_token() gives.
    const std::string token = "abcdefghijklmnopqrstuvwxyz012345";
    EXPECT_EQ(parse_pairing_url("https://[fe80::1]:443/#t=" + token + "&fp=" + kFp).token, token);
}

TEST(RequesterUniqueName, NumbersBeforeTheExtension) {
    EXPECT_EQ(numbered_name("report.pdf", 0), "report.pdf");
    EXPECT_EQ(numbered_name("report.pdf", 1), "report (1).pdf");
    EXPECT_EQ(numbered_name("report.pdf", 12), "report (12).pdf");
    EXPECT_EQ(numbered_name("archive.tar.gz", 2), "archive.tar (2).gz");
    EXPECT_EQ(numbered_name("README", 1), "README (1)");
    EXPECT_EQ(numbered_name("notes.", 1), "notes. (1)");
    // Hidden files are all stem; their own extension still counts.
    EXPECT_EQ(numbered_name(".bashrc", 1), ".bashrc (1)");
    EXPECT_EQ(numbered_name(".config.json", 1), ".config (1).json");
    EXPECT_EQ(numbered_name("..", 1), ".. (1)");
    EXPECT_EQ(numbered_name("Bericht über Öl.pdf", 3), "Bericht über Öl (3).pdf");
}

TEST(RequesterUniqueName, StaysWithinTheFileSystemsLimit) {
    const std::string longest = std::string(251, 'a') + ".pdf";
    const std::string n = numbered_name(longest, 7);
    EXPECT_EQ(n.size(), 255u);
    EXPECT_EQ(n.substr(n.size() - 8), " (7).pdf");
    // Cut at a character boundary: "ö" is two bytes.
    std::string umlauts;
    while (umlauts.size() < 251) umlauts += "ö";
    const std::string u = numbered_name(umlauts + ".txt", 1);
    EXPECT_LE(u.size(), 255u);
    EXPECT_EQ(u.substr(u.size() - 8), " (1).txt");
    const std::string stem = u.substr(0, u.size() - 8);
    EXPECT_EQ(stem.size() % 2, 0u);
    EXPECT_EQ(stem.substr(stem.size() - 2), "ö");
    // An extension too long to keep is treated as stem.
    const std::string ext = "a." + std::string(253, 'x');
    EXPECT_LE(numbered_name(ext, 1).size(), 255u);
}

TEST(RequesterDownloadDir, ReadsXdgUserDirs) {
    EXPECT_EQ(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOME/Downloads\"\n", "/home/ann"), "/home/ann/Downloads");
    EXPECT_EQ(parse_user_dirs_download("# comment\nXDG_DESKTOP_DIR=\"$HOME/Desktop\"\n"
                                       "XDG_DOWNLOAD_DIR=\"$HOME/Téléchargements\"\n",
                                       "/home/ann"),
              "/home/ann/Téléchargements");
    EXPECT_EQ(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"/data/in\"", "/home/ann"), "/data/in");
    EXPECT_EQ(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOME/with \\\"quote\"", "/h"), "/h/with \"quote");
    // Switched off ("$HOME/"), missing, relative or unquoted: the caller's default.
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOME/\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_MUSIC_DIR=\"$HOME/Music\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"dl\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=$HOME/dl", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOMEWORK/dl\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("", "/h"));
}

}  // namespace

#endif
