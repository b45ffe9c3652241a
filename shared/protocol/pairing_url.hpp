// The pairing URL a provider shows as a QR code (docs/PROTOCOL.md, "Pairing"):
//   https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT[&n=NAME.local]
// One codec for the provider, which makes it, and the requester, which reads
// it. People paste these from a phone or a screenshot, so the errors say
// which part is wrong rather than just "invalid URL".
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace umf::protocol {

struct PairingUrlError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

struct PairingUrl {
    std::string host;          // a name, dotted IPv4, or IPv6 without brackets
    bool host_is_ipv6 = false;
    bool host_is_ip = false;   // IPv4 or IPv6: no SNI for these (RFC 6066)
    unsigned short port = 443;
    std::string token;         // base64url, 22..128 characters
    std::string fingerprint;   // 64 lowercase hex digits
    // The screen's mDNS name (NAME.local), tried before `host`, which stays
    // the fallback; empty when the URL names none.
    std::string name;

    // "host:port" as an HTTP Host header and for messages: IPv6 in brackets.
    std::string authority() const {
        return (host_is_ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
    }
};

// https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT, and &n=NAME when `name` is
// given; an IPv6 host goes in brackets.
std::string format_pairing_url(const std::string& host, unsigned short port, const std::string& token,
                               const std::string& fingerprint, const std::string& name = {});

// Throws PairingUrlError with what is wrong.
PairingUrl parse_pairing_url(std::string_view url);

// True for an mDNS host name, NAME.local (RFC 1123 labels), the only kind a
// screen is announced and paired by: a pairing URL's `n`, a nearby screen.
bool is_local_host_name(std::string_view name);

// The fingerprint as 64 lowercase hex digits: accepts upper case and the
// colon-separated form ("AB:CD:...") that `openssl x509 -fingerprint` prints.
std::optional<std::string> normalise_fingerprint(std::string_view text);

}  // namespace umf::protocol
