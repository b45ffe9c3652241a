#include "native/screen_list.hpp"

#include <algorithm>
#include <cctype>
#include <map>

namespace umf::native {

namespace {

bool same_key(const std::string& a, const std::string& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](unsigned char x, unsigned char y) {
               return std::tolower(x) == std::tolower(y);
           });
}

bool is_ipv6(const std::string& address) { return address.find(':') != std::string::npos; }

// IPv4 before IPv6: the address most likely to work from a laptop comes first.
void sort_addresses(std::vector<std::string>& addresses) {
    std::sort(addresses.begin(), addresses.end(), [](const std::string& a, const std::string& b) {
        if (is_ipv6(a) != is_ipv6(b)) return !is_ipv6(a);
        return a < b;
    });
    addresses.erase(std::unique(addresses.begin(), addresses.end()), addresses.end());
}

AnnouncedScreen screen_of(const ResolvedService& r) {
    AnnouncedScreen s;
    s.name = r.name;
    s.host = r.host;
    s.port = r.port;
    if (auto fp = txt_value(r.txt, "fp"); fp && is_fingerprint(*fp)) s.fingerprint = *fp;
    if (auto v = txt_value(r.txt, "v")) s.version = *v;
    return s;
}

}  // namespace

std::optional<std::string> txt_value(const std::vector<std::string>& txt, const std::string& key) {
    for (const auto& record : txt) {
        const auto eq = record.find('=');
        if (!same_key(record.substr(0, eq), key)) continue;
        // RFC 6763 6.4: only the first occurrence of a key counts, even a
        // boolean one without a value.
        if (eq == std::string::npos) return std::nullopt;
        return record.substr(eq + 1);
    }
    return std::nullopt;
}

bool is_fingerprint(const std::string& text) {
    return text.size() == 64 &&
           std::all_of(text.begin(), text.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

std::vector<AnnouncedScreen> screens_from(const std::vector<ResolvedService>& resolved,
                                 const std::vector<std::string>& paired_fingerprints) {
    std::vector<AnnouncedScreen> screens;
    std::map<std::string, std::size_t> by_name;
    for (const auto& r : resolved) {
        if (r.port == 0) continue;
        auto [it, added] = by_name.try_emplace(r.name, screens.size());
        if (added) screens.push_back(screen_of(r));
        if (!r.address.empty()) screens[it->second].addresses.push_back(r.address);
    }
    for (auto& s : screens) {
        sort_addresses(s.addresses);
        s.paired = !s.fingerprint.empty() &&
                   std::find(paired_fingerprints.begin(), paired_fingerprints.end(), s.fingerprint) !=
                       paired_fingerprints.end();
    }
    std::sort(screens.begin(), screens.end(),
              [](const AnnouncedScreen& a, const AnnouncedScreen& b) { return a.name < b.name; });
    return screens;
}

}  // namespace umf::native
