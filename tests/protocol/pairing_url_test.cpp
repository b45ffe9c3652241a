// The pairing URL's one codec (shared/protocol/pairing_url.hpp): what the
// provider makes, the requester reads, and what pasting does to it.
#include <gtest/gtest.h>

#include <string>

#include "shared/protocol/pairing_url.hpp"

namespace {

using umf::protocol::format_pairing_url;
using umf::protocol::PairingUrl;
using umf::protocol::PairingUrlError;
using umf::protocol::parse_pairing_url;

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
    // The 32-character tokens the provider's make_token() gives.
    const std::string token = "abcdefghijklmnopqrstuvwxyz012345";
    EXPECT_EQ(parse_pairing_url("https://[fe80::1]:443/#t=" + token + "&fp=" + kFp).token, token);
}

TEST(PairingUrl, WhatIsMadeIsReadBack) {
    const std::string token = "abcdefghijklmnopqrstuvwxyz012345";
    for (const auto& [host, authority] : {std::pair<std::string, std::string>{"192.168.1.20", "192.168.1.20:47470"},
                                          {"fe80::1", "[fe80::1]:47470"},
                                          {"screen.local", "screen.local:47470"}}) {
        const std::string url = format_pairing_url(host, 47470, token, kFp);
        EXPECT_EQ(url, "https://" + authority + "/#t=" + token + "&fp=" + kFp);
        const PairingUrl p = parse_pairing_url(url);
        EXPECT_EQ(p.host, host);
        EXPECT_EQ(p.port, 47470);
        EXPECT_EQ(p.token, token);
        EXPECT_EQ(p.fingerprint, kFp);
        EXPECT_EQ(p.authority(), authority);
    }
}

}  // namespace

namespace {

TEST(PairingUrl, CarriesTheScreensLocalNameAsWell) {
    const PairingUrl u = parse_pairing_url("https://192.168.1.20:47470/" + fragment() + "&n=desk-7.local");
    EXPECT_EQ(u.host, "192.168.1.20");
    EXPECT_EQ(u.name, "desk-7.local");
    EXPECT_EQ(parse_pairing_url("https://h:1/" + fragment()).name, "");
    EXPECT_EQ(parse_pairing_url(format_pairing_url("10.0.0.5", 47470, kToken, kFp, "Desk.LOCAL")).name, "Desk.LOCAL");
    EXPECT_EQ(format_pairing_url("10.0.0.5", 47470, kToken, kFp, "desk.local"),
              "https://10.0.0.5:47470/#t=" + kToken + "&fp=" + kFp + "&n=desk.local");
    // Only an mDNS name.
    for (const char* bad : {"example.com", "local", ".local", "a..local", "-x.local", "desk.local.evil.org", ""})
        EXPECT_NE(error_of("https://h:1/" + fragment() + "&n=" + bad).find("is not a NAME.local host name"),
                  std::string::npos)
            << bad;
    EXPECT_NE(error_of("https://h:1/" + fragment() + "&n=a.local&n=b.local").find("gives 'n' twice"), std::string::npos);
}

}  // namespace
