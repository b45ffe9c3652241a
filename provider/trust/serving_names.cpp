#include "provider/trust/serving_names.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>

namespace umf::provider {

namespace {

struct Range {
    int family;
    const char* network;
    int prefix;
};

// Keep in step with the root's name constraints (root_authority.cpp).
constexpr std::array<Range, 7> kVouchedRanges{{{AF_INET, "10.0.0.0", 8},
                                               {AF_INET, "172.16.0.0", 12},
                                               {AF_INET, "192.168.0.0", 16},
                                               {AF_INET, "169.254.0.0", 16},
                                               {AF_INET, "127.0.0.0", 8},
                                               {AF_INET6, "fc00::", 7},
                                               {AF_INET6, "::1", 128}}};

bool in_range(const unsigned char* address, const unsigned char* network, int prefix) {
    for (int bit = 0; bit < prefix; ++bit) {
        const int byte = bit / 8, mask = 0x80 >> (bit % 8);
        if ((address[byte] & mask) != (network[byte] & mask)) return false;
    }
    return true;
}

void add_unique(std::vector<std::string>& list, const std::string& value) {
    if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

}  // namespace

std::string local_name_for(const std::string& host_name) {
    std::string label = host_name.substr(0, host_name.find('.'));
    for (char& c : label) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '-';
    }
    while (!label.empty() && label.front() == '-') label.erase(label.begin());
    while (!label.empty() && label.back() == '-') label.pop_back();
    if (label.size() > 63) label.resize(63);
    if (label.empty() || label == "localhost") return {};
    return label + ".local";
}

std::string local_host_name() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return {};
    return local_name_for(name);
}

bool address_may_be_vouched(const std::string& address) {
    unsigned char bytes[16];
    const int family = address.find(':') != std::string::npos ? AF_INET6 : AF_INET;
    if (inet_pton(family, address.c_str(), bytes) != 1) return false;
    for (const Range& r : kVouchedRanges) {
        if (r.family != family) continue;
        unsigned char network[16];
        inet_pton(r.family, r.network, network);
        if (in_range(bytes, network, r.prefix)) return true;
    }
    return false;
}

ServingNames serving_names(const std::string& local_name, const std::vector<std::string>& addresses) {
    ServingNames names;
    if (!local_name.empty()) names.dns.push_back(local_name);
    names.dns.push_back("localhost");
    names.addresses = {"127.0.0.1", "::1"};
    for (const auto& a : addresses) add_unique(address_may_be_vouched(a) ? names.addresses : names.not_covered, a);
    std::sort(names.addresses.begin(), names.addresses.end());
    std::sort(names.not_covered.begin(), names.not_covered.end());
    return names;
}

std::vector<std::string> current_addresses() {
    std::vector<std::string> out;
    ifaddrs* list = nullptr;
    if (::getifaddrs(&list) != 0) return out;
    for (const ifaddrs* i = list; i; i = i->ifa_next) {
        if (!i->ifa_addr || !(i->ifa_flags & IFF_UP)) continue;
        char text[INET6_ADDRSTRLEN] = {};
        if (i->ifa_addr->sa_family == AF_INET) {
            const auto* in = reinterpret_cast<const sockaddr_in*>(i->ifa_addr);
            inet_ntop(AF_INET, &in->sin_addr, text, sizeof text);
        } else if (i->ifa_addr->sa_family == AF_INET6) {
            const auto* in6 = reinterpret_cast<const sockaddr_in6*>(i->ifa_addr);
            if (IN6_IS_ADDR_LINKLOCAL(&in6->sin6_addr)) continue;
            inet_ntop(AF_INET6, &in6->sin6_addr, text, sizeof text);
        } else {
            continue;
        }
        add_unique(out, text);
    }
    ::freeifaddrs(list);
    return out;
}

ServingNames current_serving_names() { return serving_names(local_host_name(), current_addresses()); }

}  // namespace umf::provider
