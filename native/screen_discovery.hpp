// The screens announced on the network, asked of the Avahi daemon
// (libavahi-client): browses _umf._tcp in the domain "local" and resolves
// every instance it hears of, for umf-requester discover and for a
// provider's neighbours. Only built when libavahi-client was found
// (UMF_WITH_AVAHI); screen_list.hpp makes the screens of what comes back.
#pragma once

#include <stdexcept>
#include <vector>

#include "native/screen_list.hpp"

namespace umf::native {

// The Avahi daemon could not be asked, or gave up on us while browsing;
// what() is avahi_strerror's text (e.g. "Daemon not running").
struct AvahiUnreachable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Every resolved record of _umf._tcp on all interfaces, over IPv4 and IPv6:
// one per interface, protocol and instance. Returns once the daemon has said
// all it knows for now and every resolve has ended, or after `timeout_s`
// seconds with what has come by then. Throws AvahiUnreachable.
std::vector<ResolvedService> browse_screens(double timeout_s);

}  // namespace umf::native
