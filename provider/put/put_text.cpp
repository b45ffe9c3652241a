#include "provider/put/put_text.hpp"

#include <cmath>
#include <cstdio>

namespace umf::provider {

std::string human_size(std::int64_t bytes) {
    if (bytes < 0) bytes = 0;
    if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
    static const char* const units[] = {"KB", "MB", "GB", "TB", "PB"};
    double value = static_cast<double>(bytes) / 1024.0;
    int unit = 0;
    // Rounded as shown: 1023.97 KB reads "1.0 MB", not "1024 KB".
    while (unit < 4 && (value >= 10 ? std::llround(value) : std::llround(value * 10) / 10.0) >= 1024) {
        value /= 1024.0;
        ++unit;
    }
    char text[32];
    if (value < 9.95)
        std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
    else
        std::snprintf(text, sizeof text, "%lld %s", static_cast<long long>(std::llround(value)), units[unit]);
    return text;
}

std::string put_url_host(const std::string& url) {
    const auto scheme = url.find("://");
    if (scheme == std::string::npos) return url;
    const auto start = scheme + 3;
    const auto end = url.find_first_of("/?#", start);
    std::string authority = url.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (const auto at = authority.rfind('@'); at != std::string::npos) authority.erase(0, at + 1);
    if (!authority.empty() && authority.front() == '[') {
        const auto close = authority.find(']');
        return close == std::string::npos ? authority : authority.substr(0, close + 1);
    }
    if (const auto colon = authority.find(':'); colon != std::string::npos) authority.erase(colon);
    return authority.empty() ? url : authority;
}

std::string put_offer_name(const PutOffer& offer) {
    if (offer.kind == protocol::ContentKind::url) return offer.title.empty() ? put_url_host(offer.url) : offer.title;
    return offer.name.empty() ? offer.title : offer.name;
}

std::string put_offer_summary(const PutOffer& offer) {
    std::string s = "Incoming: " + put_offer_name(offer);
    if (offer.kind == protocol::ContentKind::url)
        s += " (" + offer.url + ")";
    else
        s += ", " + human_size(offer.size);
    if (!offer.client.empty()) s += ", from " + offer.client;
    return s;
}

std::string printable_text(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) {
            out += '?';
            ++i;
            continue;
        }
        if (c < 0x80) {
            out += static_cast<char>(c);
            ++i;
            continue;
        }
        // A UTF-8 sequence: its length from the lead byte; broken ones are '?'.
        const std::size_t len = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc0 ? 2 : 0;
        if (len == 0 || i + len > text.size()) {
            out += '?';
            ++i;
            continue;
        }
        char32_t cp = len == 2 ? c & 0x1f : len == 3 ? c & 0x0f : c & 0x07;
        bool ok = true;
        for (std::size_t k = 1; k < len; ++k) {
            const auto b = static_cast<unsigned char>(text[i + k]);
            if ((b & 0xc0) != 0x80) ok = false;
            cp = (cp << 6) | (b & 0x3f);
        }
        const bool control = (cp >= 0x80 && cp < 0xa0) || (cp >= 0x202a && cp <= 0x202e) ||
                             (cp >= 0x2066 && cp <= 0x2069) || cp == 0x200e || cp == 0x200f || cp == 0x061c;
        if (!ok || control) {
            out += '?';
            i += ok ? len : 1;
            continue;
        }
        out.append(text, i, len);
        i += len;
    }
    return out;
}

}  // namespace umf::provider
