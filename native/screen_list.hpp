// The screens on the network, from the services Avahi resolved (one record
// per interface, protocol and address): what umf-requester discover prints
// and a provider's neighbours are made of. Kept apart from the Avahi calls
// (screen_discovery.hpp) so that the parsing and the merging are unit-tested
// without a daemon.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace umf::native {

// The DNS-SD service type every provider announces (docs/PROTOCOL.md, "Pairing").
inline constexpr const char* kScreenServiceType = "_umf._tcp";

// One answer of an Avahi service resolver, as it came.
struct ResolvedService {
    std::string name;              // the instance name, e.g. "umf on desk" or "umf on desk (2)"
    std::string host;              // e.g. "desk.local"
    unsigned short port = 0;
    std::string address;           // textual IPv4 or IPv6 address; empty when none came
    std::vector<std::string> txt;  // the TXT strings, e.g. "v=1", "fp=..."
};

// One screen on the network, whatever number of interfaces and protocols it
// answered on.
struct AnnouncedScreen {
    std::string name;
    std::string host;
    unsigned short port = 0;
    std::vector<std::string> addresses;  // IPv4 first, then IPv6, each once
    std::string fingerprint;             // the root's, 64 lowercase hex; empty when absent or malformed
    std::string version;                 // TXT v; empty when absent
    bool paired = false;                 // its fingerprint is a pairing URL's
};

// The value of TXT key `key` (compared without case, RFC 6763 section 6.4),
// the first occurrence only; nothing for a missing key or a key without "=".
std::optional<std::string> txt_value(const std::vector<std::string>& txt, const std::string& key);

// True for exactly 64 lowercase hex digits, the form the provider announces.
bool is_fingerprint(const std::string& text);

// One screen per instance name, sorted by name. Host, port and TXT come from
// the first record of a name; every record adds its address. Records without
// a port are dropped: nothing could connect to them. A screen whose
// fingerprint is one of `paired_fingerprints` (the pairing URL's, the kept
// screens') is marked paired.
std::vector<AnnouncedScreen> screens_from(const std::vector<ResolvedService>& resolved,
                                 const std::vector<std::string>& paired_fingerprints = {});

}  // namespace umf::native
