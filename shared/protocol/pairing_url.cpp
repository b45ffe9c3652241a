#include "shared/protocol/pairing_url.hpp"

#include <arpa/inet.h>

#include <cstddef>

namespace umf::protocol {
namespace {


bool is_base64url(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
}

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// QR generators and chat programs sometimes percent-encode the fragment
// (":" as %3A); a malformed escape is an error, not passed through.
std::string percent_decode(std::string_view s, const char* what) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '%') {
            out += s[i];
            continue;
        }
        if (i + 2 >= s.size() || hex_value(s[i + 1]) < 0 || hex_value(s[i + 2]) < 0)
            throw PairingUrlError(std::string("the pairing URL's ") + what + " has a broken %-escape");
        out += static_cast<char>(hex_value(s[i + 1]) * 16 + hex_value(s[i + 2]));
        i += 2;
    }
    return out;
}

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

// A DNS name (RFC 1123 labels) or a dotted IPv4 address.
bool is_host_name(std::string_view h) {
    if (h.empty() || h.size() > 253) return false;
    std::size_t label = 0;
    char prev = '.';
    for (char c : h) {
        if (c == '.') {
            if (label == 0 || prev == '-') return false;
            label = 0;
        } else if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-') {
            if (label == 0 && c == '-') return false;
            if (++label > 63) return false;
        } else {
            return false;
        }
        prev = c;
    }
    return prev != '-';
}

bool looks_like_ipv4(std::string_view h) {
    for (char c : h)
        if (c != '.' && (c < '0' || c > '9')) return false;
    return !h.empty();
}

}  // namespace

std::string format_pairing_url(const std::string& host, unsigned short port, const std::string& token,
                               const std::string& fingerprint, const std::string& name) {
    const bool ipv6 = host.find(':') != std::string::npos && host.front() != '[';
    return "https://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port) + "/#t=" + token +
           "&fp=" + fingerprint + (name.empty() ? "" : "&n=" + name);
}

bool is_local_host_name(std::string_view name) {
    return name.size() > 6 && iequals(name.substr(name.size() - 6), ".local") && is_host_name(name);
}

std::optional<std::string> normalise_fingerprint(std::string_view text) {
    const bool colons = text.find(':') != std::string_view::npos;
    std::string hex;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        // With colons, every group is exactly two digits: "ab:cd", never "a:bcd".
        if (colons && i % 3 == 2) {
            if (c != ':') return std::nullopt;
            continue;
        }
        const int v = hex_value(c);
        if (v < 0) return std::nullopt;
        hex += "0123456789abcdef"[v];
    }
    if (hex.size() != 64 || (colons && text.size() != 64 + 31)) return std::nullopt;
    return hex;
}

PairingUrl parse_pairing_url(std::string_view url) {
    // Pasted from a terminal or a QR app, it may carry surrounding spaces.
    while (!url.empty() && (url.front() == ' ' || url.front() == '\t' || url.front() == '\n' || url.front() == '\r'))
        url.remove_prefix(1);
    while (!url.empty() && (url.back() == ' ' || url.back() == '\t' || url.back() == '\n' || url.back() == '\r'))
        url.remove_suffix(1);
    if (url.empty()) throw PairingUrlError("the pairing URL is empty");
    for (char c : url)
        if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f)
            throw PairingUrlError("the pairing URL contains spaces or control characters");

    const auto scheme_end = url.find("://");
    if (scheme_end == std::string_view::npos)
        throw PairingUrlError("the pairing URL must start with https:// (it looks like https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT)");
    if (!iequals(url.substr(0, scheme_end), "https"))
        throw PairingUrlError("the pairing URL must use https, not '" + std::string(url.substr(0, scheme_end)) + "'");
    std::string_view rest = url.substr(scheme_end + 3);

    const auto hash = rest.find('#');
    if (hash == std::string_view::npos)
        throw PairingUrlError("the pairing URL has no #t=TOKEN&fp=FINGERPRINT part; copy the whole URL");
    std::string_view fragment = rest.substr(hash + 1);
    rest = rest.substr(0, hash);
    const auto path_start = rest.find_first_of("/?");
    std::string_view authority = rest.substr(0, path_start);
    if (path_start != std::string_view::npos) {
        const std::string_view path = rest.substr(path_start);
        if (path != "/" && path != "/?")
            throw PairingUrlError("the pairing URL should have no path before the '#', found '" + std::string(path) + "'");
    }
    if (authority.find('@') != std::string_view::npos)
        throw PairingUrlError("the pairing URL must not contain a user name ('@')");

    PairingUrl out;
    std::string_view port_text;
    if (!authority.empty() && authority.front() == '[') {
        const auto close = authority.find(']');
        if (close == std::string_view::npos) throw PairingUrlError("the pairing URL's IPv6 address lacks its ']'");
        out.host = std::string(authority.substr(1, close - 1));
        const std::string_view after = authority.substr(close + 1);
        if (!after.empty()) {
            if (after.front() != ':') throw PairingUrlError("unexpected text after the IPv6 address in the pairing URL");
            port_text = after.substr(1);
            if (port_text.empty()) throw PairingUrlError("the pairing URL has a ':' but no port");
        }
        in6_addr addr{};
        if (inet_pton(AF_INET6, out.host.c_str(), &addr) != 1)
            throw PairingUrlError("'" + out.host + "' in the pairing URL is not an IPv6 address");
        out.host_is_ipv6 = out.host_is_ip = true;
    } else {
        const auto colon = authority.rfind(':');
        out.host = std::string(authority.substr(0, colon));
        if (colon != std::string_view::npos) {
            port_text = authority.substr(colon + 1);
            if (port_text.empty()) throw PairingUrlError("the pairing URL has a ':' but no port");
        }
        if (out.host.find(':') != std::string::npos)
            throw PairingUrlError("an IPv6 address in the pairing URL must be in brackets: https://[ADDRESS]:PORT/");
        if (out.host.empty()) throw PairingUrlError("the pairing URL has no host");
        if (looks_like_ipv4(out.host)) {
            in_addr addr{};
            if (inet_pton(AF_INET, out.host.c_str(), &addr) != 1)
                throw PairingUrlError("'" + out.host + "' in the pairing URL is not an IPv4 address");
            out.host_is_ip = true;
        } else if (!is_host_name(out.host)) {
            throw PairingUrlError("'" + out.host + "' in the pairing URL is not a host name");
        }
    }
    if (!port_text.empty()) {
        unsigned long port = 0;
        for (char c : port_text) {
            if (c < '0' || c > '9' || port > 65535)
                throw PairingUrlError("the pairing URL's port '" + std::string(port_text) + "' is not a number");
            port = port * 10 + static_cast<unsigned long>(c - '0');
        }
        if (port == 0 || port > 65535 || port_text.size() > 5)
            throw PairingUrlError("the pairing URL's port " + std::string(port_text) + " is not within 1..65535");
        out.port = static_cast<unsigned short>(port);
    }

    std::optional<std::string> token, fingerprint, name;
    while (!fragment.empty()) {
        const auto amp = fragment.find('&');
        const std::string_view item = fragment.substr(0, amp);
        fragment = amp == std::string_view::npos ? std::string_view() : fragment.substr(amp + 1);
        if (item.empty()) continue;
        const auto eq = item.find('=');
        const std::string_view key = item.substr(0, eq);
        const std::string_view value = eq == std::string_view::npos ? std::string_view() : item.substr(eq + 1);
        // Later versions may add parameters; only ours are checked.
        std::optional<std::string>* slot = key == "t" ? &token : key == "fp" ? &fingerprint : key == "n" ? &name : nullptr;
        if (!slot) continue;
        if (*slot) throw PairingUrlError("the pairing URL gives '" + std::string(key) + "' twice");
        *slot = percent_decode(value, key == "t" ? "token" : key == "fp" ? "fingerprint" : "name");
    }
    if (!token) throw PairingUrlError("the pairing URL has no token (t=...) after the '#'");
    if (!fingerprint) throw PairingUrlError("the pairing URL has no certificate fingerprint (fp=...) after the '#'");
    if (token->size() < 22 || token->size() > 128)
        throw PairingUrlError("the pairing URL's token has " + std::to_string(token->size()) +
                              " characters; a token has 22 to 128");
    for (char c : *token)
        if (!is_base64url(c))
            throw PairingUrlError("the pairing URL's token may hold only letters, digits, '-' and '_'");
    auto fp = normalise_fingerprint(*fingerprint);
    if (!fp)
        throw PairingUrlError("the pairing URL's fingerprint must be 64 hex digits (SHA-256), optionally as "
                              "colon-separated pairs");
    if (name) {
        // Only an mDNS name: the one the screen announces on its local network.
        if (!is_local_host_name(*name))
            throw PairingUrlError("the pairing URL's name '" + *name + "' is not a NAME.local host name");
        out.name = std::move(*name);
    }
    out.token = std::move(*token);
    out.fingerprint = std::move(*fp);
    return out;
}

}  // namespace umf::protocol
