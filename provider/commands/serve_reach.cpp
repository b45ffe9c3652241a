#include "provider/commands/serve_reach.hpp"

#include <iostream>

#include "provider/commands/common_options.hpp"
#include "provider/net/server.hpp"
#include "provider/trust/root_export.hpp"

namespace umf::provider {

std::string LocalName::get() const {
    std::lock_guard lock(mutex_);
    return announced_.empty() ? local_host_name() : announced_;
}

void LocalName::set(const std::string& name) {
    std::lock_guard lock(mutex_);
    announced_ = name;
}

std::unique_ptr<CertificateKeeper> keep_certificate(const std::filesystem::path& config_dir, Server& server,
                                                    std::shared_ptr<const LocalName> name, ServingNames served) {
    CertificateKeeper::Settings settings;
    settings.config_dir = config_dir;
    settings.names = [name = std::move(name)] { return serving_names(name->get(), current_addresses()); };
    settings.issued = [&server](const TlsIdentity& identity, const std::string& why) {
        try {
            server.replace_identity(identity);
            std::cout << "certificate: issued again by the screen's root (" << why << ")\n" << std::flush;
        } catch (const std::exception& e) {
            std::cerr << "umf-provider: the certificate issued again cannot be served: " << e.what() << "\n";
        }
    };
    settings.failed = [](const std::string& error) {
        std::cerr << "umf-provider: cannot issue the certificate again: " << error << "; the old one serves on\n";
    };
    return std::make_unique<CertificateKeeper>(std::move(settings), std::move(served));
}

void offer_root(StaticSite& site, const RootAuthority& root) {
    site.add(kRootDerPath, {"application/x-x509-ca-cert",
                            std::make_shared<const std::string>(export_root(root, RootForm::der)), "umf-root.crt"});
    site.add(kRootProfilePath, {"application/x-apple-aspen-config",
                                std::make_shared<const std::string>(export_root(root, RootForm::mobileconfig)),
                                "umf-root.mobileconfig"});
}

std::unique_ptr<AvahiAnnouncement> announce_on_network(unsigned short port, const std::string& fingerprint,
                                                       std::shared_ptr<LocalName> name) {
    Announcement wanted;
    const std::string host = local_host_name();
    wanted.instance = "umf on " + (host.empty() ? std::string("this screen") : host.substr(0, host.find('.')));
    wanted.port = port;
    wanted.txt = {"v=1", "fp=" + fingerprint};
    return std::make_unique<AvahiAnnouncement>(
        wanted, [name = std::move(name), port](const Announcement& made, const std::string& why_not) {
            if (!why_not.empty()) {
                std::cout << "announced: nowhere (" << why_not << "); phones find this screen by its address only\n"
                          << std::flush;
                return;
            }
            name->set(made.host_name);
            std::cout << "announced: \"" << made.instance << "\" (" << native::kScreenServiceType << ") at https://"
                      << made.host_name << ":" << port << " through Avahi\n"
                      << std::flush;
        });
}

std::unique_ptr<NearbyBrowse> browse_nearby(const std::string& fingerprint, std::shared_ptr<NearbyScreens> nearby) {
    NearbyBrowse::Settings settings;
    settings.own_fingerprint = fingerprint;
    settings.changed = [](const std::vector<NearbyScreen>& screens, const std::string& why_not) {
        if (!why_not.empty()) {
            std::cout << "nearby: not listed (" << why_not << ")\n" << std::flush;
            return;
        }
        std::string line = "nearby: " + std::to_string(screens.size()) + " other screen(s)";
        for (std::size_t i = 0; i < screens.size(); ++i)
            line += (i ? ", \"" : ": \"") + screens[i].name + "\" at " + screens[i].origin;
        std::cout << line << "\n" << std::flush;
    };
    return std::make_unique<NearbyBrowse>(std::move(settings), std::move(nearby));
}

void print_where_served(const std::string& bind, unsigned short port, const ServingNames& names,
                        const std::string& fingerprint, std::ostream& out) {
    // 0.0.0.0 listens on IPv4 only; "::" on both.
    const bool all_v4 = bind == "0.0.0.0", all = all_v4 || bind == "::";
    std::string where;
    for (const auto& d : names.dns)
        if (all || (is_loopback(bind) && d == "localhost")) where += " " + https_origin(d, port);
    for (const auto& address : names.addresses)
        if (all ? !(all_v4 && address.find(':') != std::string::npos) : address == bind)
            where += " " + https_origin(address, port);
    out << "serving at:" << where << "\n";
    std::string list;
    for (const auto& a : names.not_covered)
        if (all && !(all_v4 && a.find(':') != std::string::npos)) list += (list.empty() ? "" : ", ") + a;
    if (!list.empty())
        out << "  also at " << list << ", which the screen's root may not vouch for (not a private address): "
            << "phones there see a certificate warning\n";
    out << "screen root (SHA-256): " << fingerprint
        << "\n  phones that trust it open the page without a warning: \"Trust this screen\" on the phone page, "
           "or umf-provider trust\n";
}

}  // namespace umf::provider
