#include "requester/discover_command.hpp"

#include <cerrno>
#include <cstring>
#include <vector>

#include "requester/cli.hpp"
#include "requester/paired_screens.hpp"
#include "requester/screen_lines.hpp"
#include "shared/protocol/pairing_url.hpp"
#ifdef UMF_WITH_AVAHI
#include "native/screen_discovery.hpp"
#endif

namespace umf::requester {

const char* const kDiscoverUsage = R"(umf-requester discover: list the screens on the local network

usage:
  umf-requester discover [--timeout S] [--json] [--url URL]

Asks the Avahi daemon for the providers that announce themselves over DNS-SD
(_umf._tcp in the domain local, on every interface, over IPv4 and IPv6) and
prints one line per screen, sorted by name:
  umf on desk  https://desk.local:47470  192.168.1.20,fe80::1%wlan0  fp 1a2b...
A screen heard on several interfaces or over both protocols is listed once,
with all its addresses. The fingerprint (fp) is the SHA-256 of the screen's
root certificate, the one its pairing URL pins; "no fingerprint" when the
screen announces none or a malformed one. The pairing token is never
announced: to grab or put, a screen's pairing URL (umf-provider pair) is
still needed.

options:
  --timeout S  stop listening after S seconds (default 3); discover stops earlier
               once Avahi has said all it knows and every screen is resolved
  --json       one JSON object per line instead:
                 {"name":"umf on desk","host":"desk.local","port":47470,
                  "addresses":["192.168.1.20"],"fingerprint":"<64 hex>","version":"1"}
               ("fingerprint" and "version" only when announced)
  --url URL    a pairing URL: the screen with its fingerprint is marked (paired),
               in JSON "paired":true (false on the others); the screens kept with
               umf-requester pair are marked so without it

exit codes: 0 screens were found; 2 wrong usage; 3 built without Avahi support;
            4 the Avahi daemon could not be asked (not running, no system bus);
            5 no screen answered within S seconds (nothing on stdout).
)";

namespace {

void write_text_line(std::FILE* out, const std::string& line) {
    if (std::fprintf(out, "%s\n", line.c_str()) < 0 || std::fflush(out) != 0)
        throw InputError(std::string("cannot write the output: ") + std::strerror(errno));
}

}  // namespace

DiscoverOptions parse_discover_args(int argc, char** argv, int first) {
    const Args a = parse_args(argc, argv, first, {"timeout", "url"}, {"json"});
    if (!a.positional.empty()) throw UsageError("discover takes no arguments, not '" + a.positional.front() + "'");
    DiscoverOptions o;
    if (auto t = get(a, "timeout")) o.timeout_s = parse_seconds(*t);
    o.json = has_flag(a, "json");
    if (auto url = get(a, "url")) {
        try {
            o.paired_fingerprints.push_back(protocol::parse_pairing_url(*url).fingerprint);
        } catch (const protocol::PairingUrlError& e) {
            throw UsageError(std::string("--url: ") + e.what());
        }
    }
    try {
        for (const auto& kept : read_paired_screens(default_paired_screens_file()))
            o.paired_fingerprints.push_back(kept.url.fingerprint);
    } catch (const InputError& e) {
        std::fprintf(stderr, "discover: %s; the screens kept there are not marked\n", e.what());
    }
    return o;
}

int run_discover(const DiscoverOptions& o, std::FILE* out) {
#ifdef UMF_WITH_AVAHI
    std::vector<native::ResolvedService> resolved;
    try {
        resolved = native::browse_screens(o.timeout_s);
    } catch (const native::AvahiUnreachable& e) {
        std::fprintf(stderr,
                     "discover: cannot ask Avahi (%s); is avahi-daemon running? "
                     "A screen can still be reached by its pairing URL.\n",
                     e.what());
        return kConnection;
    }
    const std::vector<native::AnnouncedScreen> screens = native::screens_from(resolved, o.paired_fingerprints);
    if (screens.empty()) {
        std::fprintf(stderr, "discover: no screen answered within %g s\n", o.timeout_s);
        return kNothing;
    }
    for (const auto& s : screens) write_text_line(out, o.json ? screen_json(s, !o.paired_fingerprints.empty()) : screen_line(s));
    return kOk;
#else
    (void)o;
    (void)out;
    std::fputs("discover: this umf-requester was built without Avahi support (libavahi-client-dev); "
               "a screen can still be reached by its pairing URL.\n",
               stderr);
    return kInputError;
#endif
}

}  // namespace umf::requester
