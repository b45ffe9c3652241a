// The names and addresses the provider's serving certificate is made for:
// this host's .local name (mDNS), localhost, the loopback addresses and
// every current address of the machine that the screen's root may vouch
// for (root_authority.hpp: private, link-local and loopback ranges only).
#pragma once

#include <string>
#include <vector>

namespace umf::provider {

struct ServingNames {
    std::vector<std::string> dns;        // "host.local", "localhost"
    std::vector<std::string> addresses;  // textual IPv4 and IPv6, sorted, no duplicates
    // Current addresses outside the root's ranges (a public IPv4, a global
    // IPv6): served, but no certificate of the screen's may name them.
    std::vector<std::string> not_covered;

    friend bool operator==(const ServingNames&, const ServingNames&) = default;
};

// "name.local" from a host name: its first label, lower case, with what DNS
// labels cannot hold replaced by '-'; empty when nothing usable is left or
// the name is localhost.
std::string local_name_for(const std::string& host_name);

// This machine's .local name (from gethostname), empty when it has none.
std::string local_host_name();

// True when the address (textual) is in the root's permitted ranges:
// 10/8, 172.16/12, 192.168/16, 169.254/16, 127/8, fc00::/7, ::1.
bool address_may_be_vouched(const std::string& address);

// The names for `local_name` and `addresses` (the machine's, from
// current_addresses()): sorted and split into covered and not.
ServingNames serving_names(const std::string& local_name, const std::vector<std::string>& addresses);

// Every address of the machine's interfaces that are up (getifaddrs), IPv4
// and IPv6 without link-local IPv6 (a URL cannot carry its zone).
std::vector<std::string> current_addresses();

// serving_names(local_host_name(), current_addresses()).
ServingNames current_serving_names();

}  // namespace umf::provider
