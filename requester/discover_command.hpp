// umf-requester discover: the screens that announce themselves on the local
// network (DNS-SD _umf._tcp through Avahi), one line each. A listing only:
// the token is never announced, so connecting still needs a pairing URL.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace umf::requester {

extern const char* const kDiscoverUsage;

struct DiscoverOptions {
    double timeout_s = 3;
    bool json = false;
    // From --url and the screens kept with `umf-requester pair`.
    std::vector<std::string> paired_fingerprints;
};

// argv[first..] of "umf-requester discover ...". Throws UsageError.
DiscoverOptions parse_discover_args(int argc, char** argv, int first);

// Lists the screens on `out`, messages on stderr; returns kOk, kInputError
// (built without Avahi), kConnection (Avahi unreachable) or kNothing.
int run_discover(const DiscoverOptions& options, std::FILE* out);

}  // namespace umf::requester
