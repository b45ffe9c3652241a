#include "provider/commands/trust_command.hpp"

#include <fstream>

#include "provider/commands/common_options.hpp"
#include "provider/commands/control_client.hpp"
#include "provider/trust/root_export.hpp"
#include "provider/trust/tls_identity_store.hpp"

namespace umf::provider {

using cli::has_flag;
using cli::UsageError;

namespace {

int export_to(const RootAuthority& root, const cli::Args& a, std::ostream& out, std::ostream& err) {
    if (a.positional.size() != 2) throw UsageError("trust export takes one FILE (- for standard output)");
    if (has_flag(a, "der") && has_flag(a, "mobileconfig")) throw UsageError("--der or --mobileconfig, not both");
    const RootForm form = has_flag(a, "der")            ? RootForm::der
                          : has_flag(a, "mobileconfig") ? RootForm::mobileconfig
                                                        : RootForm::pem;
    const std::string bytes = export_root(root, form);
    const std::string& file = a.positional[1];
    if (file == "-") {
        out << bytes << std::flush;
        return kOk;
    }
    // The root's certificate is public (every handshake sends it): an
    // ordinary file, unlike its key.
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    f << bytes;
    f.close();
    if (!f) {
        err << "umf-provider: cannot write " << file << "\n";
        return kConfigError;
    }
    err << "umf-provider: the screen's root written to " << file << " (SHA-256 " << root.fingerprint << ")\n";
    return kOk;
}

void describe(const RootAuthority& root, const cli::Args& a, std::ostream& out) {
    const unsigned short port = running_provider_port(a).value_or(kDefaultPort);
    const std::string host = url_host(a, "0.0.0.0");
    const std::string origin = https_origin(host, port);
    out << "screen root (SHA-256): " << root.fingerprint << "\n"
        << "  for people:          " << fingerprint_for_people(root.fingerprint) << "\n"
        << "It may vouch only for .local names, localhost and private, link-local and loopback addresses.\n"
        << "A phone gets it from the phone page (" << origin << "/, \"Trust this screen\"), or directly:\n"
        << "  Android: " << origin << kRootDerPath << "\n"
        << "  iOS:     " << origin << kRootProfilePath << "\n"
        << "Compare the fingerprint the phone shows with the one above. Elsewhere:\n"
        << "  umf-provider trust export FILE [--der | --mobileconfig]\n";
}

}  // namespace

int run_trust(const cli::Args& a, std::ostream& out, std::ostream& err) {
    const bool exporting = !a.positional.empty() && a.positional[0] == "export";
    if (!a.positional.empty() && !exporting) throw UsageError("trust takes no word but export");
    if (!exporting && (has_flag(a, "der") || has_flag(a, "mobileconfig")))
        throw UsageError("--der and --mobileconfig go with trust export FILE");
    try {
        const RootAuthority root = load_or_create_root(config_dir_option(a));
        if (exporting) return export_to(root, a, out, err);
        describe(root, a, out);
    } catch (const UsageError&) {
        throw;
    } catch (const std::exception& e) {
        err << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }
    return kOk;
}

}  // namespace umf::provider
