#include "native/screen_discovery.hpp"

#include <avahi-client/client.h>
#include <avahi-client/lookup.h>
#include <avahi-common/address.h>
#include <avahi-common/error.h>
#include <avahi-common/simple-watch.h>
#include <avahi-common/strlst.h>
#include <avahi-common/timeval.h>
#include <net/if.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace umf::native {

namespace {

constexpr const char* kDomain = "local";

struct PollFree {
    void operator()(AvahiSimplePoll* p) const { avahi_simple_poll_free(p); }
};
struct ClientFree {
    void operator()(AvahiClient* c) const { avahi_client_free(c); }  // frees its browser and resolvers too
};

// A link-local IPv6 address is useless without its interface: fe80::1%eth0.
std::string address_text(const AvahiAddress* a, AvahiIfIndex interface) {
    if (!a) return {};
    char text[AVAHI_ADDRESS_STR_MAX];
    if (!avahi_address_snprint(text, sizeof text, a)) return {};
    std::string out = text;
    const bool link_local = a->proto == AVAHI_PROTO_INET6 && a->data.ipv6.address[0] == 0xfe &&
                            (a->data.ipv6.address[1] & 0xc0) == 0x80;
    char name[IF_NAMESIZE];
    if (link_local && interface >= 0 && if_indextoname(static_cast<unsigned>(interface), name)) out += "%" + std::string(name);
    return out;
}

std::vector<std::string> txt_strings(AvahiStringList* txt) {
    std::vector<std::string> out;
    for (AvahiStringList* l = txt; l; l = avahi_string_list_get_next(l))
        out.emplace_back(reinterpret_cast<const char*>(avahi_string_list_get_text(l)), avahi_string_list_get_size(l));
    return out;
}

// One browse on a simple poll loop of its own: the loop runs until the
// browser has said all it knows, every resolve has ended, the deadline
// passes or the daemon fails us.
class Browse {
public:
    explicit Browse(double timeout_s) : poll_(avahi_simple_poll_new()), timeout_s_(timeout_s) {
        if (!poll_) throw std::bad_alloc();
    }

    std::vector<ResolvedService> run() {
        int error = 0;
        client_.reset(avahi_client_new(avahi_simple_poll_get(poll_.get()), AvahiClientFlags(0), on_client, this, &error));
        if (!client_) throw AvahiUnreachable(avahi_strerror(error));
        if (!avahi_service_browser_new(client_.get(), AVAHI_IF_UNSPEC, AVAHI_PROTO_UNSPEC, kScreenServiceType, kDomain,
                                       AvahiLookupFlags(0), on_browse, this))
            throw AvahiUnreachable(avahi_strerror(avahi_client_errno(client_.get())));
        const AvahiPoll* api = avahi_simple_poll_get(poll_.get());
        timeval deadline;
        avahi_elapse_time(&deadline, static_cast<unsigned>(std::ceil(timeout_s_ * 1000)), 0);
        api->timeout_new(api, &deadline, on_timeout, this);  // freed with the poll
        avahi_simple_poll_loop(poll_.get());
        if (error_) throw AvahiUnreachable(avahi_strerror(*error_));
        std::vector<ResolvedService> out;
        for (auto& f : found_) out.push_back(std::move(f.service));
        return out;
    }

private:
    struct Found {
        AvahiIfIndex interface;
        AvahiProtocol protocol;
        ResolvedService service;
    };

    void quit() { avahi_simple_poll_quit(poll_.get()); }

    void fail(int error) {
        error_ = error;
        quit();
    }

    void quit_if_done() {
        if (all_for_now_ && pending_ == 0) quit();
    }

    static void on_client(AvahiClient* c, AvahiClientState state, void* self) {
        // The daemon went away (restarted, stopped) while we were browsing.
        if (state == AVAHI_CLIENT_FAILURE) static_cast<Browse*>(self)->fail(avahi_client_errno(c));
    }

    static void on_timeout(AvahiTimeout*, void* self) { static_cast<Browse*>(self)->quit(); }

    static void on_browse(AvahiServiceBrowser* b, AvahiIfIndex interface, AvahiProtocol protocol, AvahiBrowserEvent event,
                          const char* name, const char* type, const char* domain, AvahiLookupResultFlags,
                          void* self_) {
        auto* self = static_cast<Browse*>(self_);
        switch (event) {
            case AVAHI_BROWSER_NEW:
                // The address in the same protocol as the record: a screen
                // heard over both gives both its addresses.
                if (avahi_service_resolver_new(avahi_service_browser_get_client(b), interface, protocol, name, type,
                                               domain, protocol, AvahiLookupFlags(0), on_resolve, self))
                    ++self->pending_;
                break;
            case AVAHI_BROWSER_REMOVE:
                std::erase_if(self->found_, [&](const Found& f) {
                    return f.interface == interface && f.protocol == protocol && f.service.name == name;
                });
                break;
            case AVAHI_BROWSER_ALL_FOR_NOW:
                self->all_for_now_ = true;
                self->quit_if_done();
                break;
            case AVAHI_BROWSER_CACHE_EXHAUSTED: break;
            case AVAHI_BROWSER_FAILURE: self->fail(avahi_client_errno(avahi_service_browser_get_client(b))); break;
        }
    }

    static void on_resolve(AvahiServiceResolver* r, AvahiIfIndex interface, AvahiProtocol protocol,
                           AvahiResolverEvent event, const char* name, const char*, const char*, const char* host,
                           const AvahiAddress* address, uint16_t port, AvahiStringList* txt, AvahiLookupResultFlags,
                           void* self_) {
        auto* self = static_cast<Browse*>(self_);
        // A failed resolve is an instance that went away or never answered:
        // nothing to list, not an error of the command.
        if (event == AVAHI_RESOLVER_FOUND)
            self->found_.push_back(
                {interface, protocol, {name, host ? host : "", port, address_text(address, interface), txt_strings(txt)}});
        avahi_service_resolver_free(r);
        --self->pending_;
        self->quit_if_done();
    }

    std::unique_ptr<AvahiSimplePoll, PollFree> poll_;
    std::unique_ptr<AvahiClient, ClientFree> client_;  // declared after poll_: freed before it
    double timeout_s_;
    int pending_ = 0;
    bool all_for_now_ = false;
    std::optional<int> error_;
    std::vector<Found> found_;
};

}  // namespace

std::vector<ResolvedService> browse_screens(double timeout_s) { return Browse(timeout_s).run(); }

}  // namespace umf::native
