// The pairing URL (shared/protocol/pairing_url.hpp), which people paste from
// a phone, a chat or a screenshot: any text is either refused with
// PairingUrlError or read, and a URL as read, formatted again, reads the same
// (the provider makes what the requester reads with one codec).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "shared/protocol/pairing_url.hpp"

namespace p = umf::protocol;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    (void)p::normalise_fingerprint(text);
    p::PairingUrl url;
    try {
        url = p::parse_pairing_url(text);
    } catch (const p::PairingUrlError&) {
        return 0;
    }
    (void)url.authority();
    const p::PairingUrl again =
        p::parse_pairing_url(p::format_pairing_url(url.host, url.port, url.token, url.fingerprint, url.name));
    if (again.host != url.host || again.port != url.port || again.token != url.token || again.name != url.name ||
        again.fingerprint != url.fingerprint || again.host_is_ipv6 != url.host_is_ipv6 || again.host_is_ip != url.host_is_ip)
        __builtin_trap();
    return 0;
}
