// umf-requester discover's pure half: the services Avahi resolved, one record
// per interface, protocol and address, turned into the list of screens it
// prints. Kept apart from the Avahi calls (screen_discovery.hpp) so that the
// parsing, the merging and the lines are unit-tested without a daemon.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace umf::requester {

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
struct Screen {
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
std::vector<Screen> screens_from(const std::vector<ResolvedService>& resolved,
                                 const std::vector<std::string>& paired_fingerprints = {});

// "umf on desk  https://desk.local:8443  10.0.0.5  fp HEX", "  (paired)" at
// the end when paired. Control characters an announcer put in a name are
// shown as '?' so that one screen is always one line.
std::string screen_line(const Screen& screen);

// {"name":...,"host":...,"port":...,"addresses":[...],"fingerprint":...,
// "version":...}; "fingerprint" and "version" only when known, "paired" only
// when `with_paired` (discover --url, or screens kept with pair). Bytes that are not UTF-8 become U+FFFD.
std::string screen_json(const Screen& screen, bool with_paired);

}  // namespace umf::requester
