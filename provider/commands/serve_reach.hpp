// How phones and webcams reach a serving provider (steps of `serve`, which
// serve_command.cpp composes): the serving certificate kept fitting the
// machine, the root offered to phones, the announcement on the local
// network, and the console's word on where it serves and which root vouches
// for it.
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>

#include "provider/discovery/avahi_announcement.hpp"
#include "provider/discovery/nearby_browse.hpp"
#include "provider/service/static_site.hpp"
#include "provider/trust/certificate_keeper.hpp"
#include "provider/trust/root_authority.hpp"
#include "provider/trust/serving_names.hpp"

namespace umf::provider {

class Server;

// This host's .local name: the host name's until Avahi says which it
// announced (it takes another on a collision); the serving certificate
// names it.
class LocalName {
public:
    std::string get() const;
    void set(const std::string& name);

private:
    mutable std::mutex mutex_;
    std::string announced_;
};

// Issues the serving certificate again when the machine's names or
// addresses change or its end nears (`served`: what it names now); `server`
// serves the new one from the next handshake. Keep the keeper no longer
// than the server.
std::unique_ptr<CertificateKeeper> keep_certificate(const std::filesystem::path& config_dir, Server& server,
                                                    std::shared_ptr<const LocalName> name, ServingNames served);

// "Trust this screen" on the phone page: the root in both forms phones
// install (trust/root_export.hpp), added to the site.
void offer_root(StaticSite& site, const RootAuthority& root);

// _umf._tcp on the local network through Avahi, with the root's fingerprint
// (public, and what tells one screen from another), never the token; the
// outcome goes to the console and the name Avahi announced to `name`.
std::unique_ptr<AvahiAnnouncement> announce_on_network(unsigned short port, const std::string& fingerprint,
                                                       std::shared_ptr<LocalName> name);

// "serving at: https://..." for the origins a phone can open at `bind`, the
// addresses the root may not vouch for, and the root's fingerprint.
// Keeps the list of the other screens announced nearby for the phone page
// (/nearby.json), and says on the console when it changes.
std::unique_ptr<NearbyBrowse> browse_nearby(const std::string& fingerprint, std::shared_ptr<NearbyScreens> nearby);

void print_where_served(const std::string& bind, unsigned short port, const ServingNames& names,
                        const std::string& fingerprint, std::ostream& out);

}  // namespace umf::provider
