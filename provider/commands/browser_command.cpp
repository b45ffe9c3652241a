#include "provider/commands/browser_command.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "provider/browser/browser_status.hpp"
#include "provider/browser/host_manifests.hpp"
#include "provider/commands/common_options.hpp"
#include "provider/commands/control_client.hpp"
#include "provider/common/install_paths.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::provider {

namespace {

namespace fs = std::filesystem;
using cli::get;
using cli::has_flag;
using cli::UsageError;

int run_install(const cli::Args& a, std::ostream& out, std::ostream& err) {
    if (get(a, "prefix") && !has_flag(a, "system")) throw UsageError("--prefix goes with --system");
    fs::path host = get(a, "host") ? fs::path(*get(a, "host")) : program_dir() / "umf-browser-host";
    std::error_code ec;
    host = fs::absolute(host, ec);
    if (::access(host.c_str(), X_OK) != 0) {
        err << "umf-provider: no umf-browser-host at " << host.string()
            << " (it is installed beside umf-provider; give its place with --host PATH)\n";
        return kConfigError;
    }
    HostManifestPlaces places;
    const char* home = std::getenv("HOME");
    const char* config = std::getenv("XDG_CONFIG_HOME");
    places.home = home && *home ? fs::path(home) : fs::path();
    places.config_home = config && *config ? fs::path(config) : fs::path();
    places.system = has_flag(a, "system");
    if (get(a, "prefix")) places.prefix = fs::absolute(*get(a, "prefix"), ec);
    if (!places.system && places.home.empty()) {
        err << "umf-provider: HOME is not set, so there is no per-user place for the host manifests\n";
        return kConfigError;
    }
    for (const HostManifest& m : host_manifests(host, places)) {
        fs::create_directories(m.file.parent_path(), ec);
        try {
            write_file_atomically(m.file.string(), m.text);
            ::chmod(m.file.c_str(), 0644);
        } catch (const std::exception& e) {
            err << "umf-provider: " << e.what() << "\n";
            return kConfigError;
        }
        out << m.browser << ": " << m.file.string() << "\n";
    }
    const auto ext = browser_extension_dir();
    const std::string dir = ext ? ext->string() : std::string("PREFIX/share/umf/browser-extension");
    out << "host: " << host.string() << "\n"
        << "Now load the extension (" << dir << "):\n"
        << "  Chromium, Chrome, Edge: open chrome://extensions, turn on Developer mode, \"Load unpacked\", choose "
        << dir << "\n"
        << "  Firefox: open about:debugging#/runtime/this-firefox, \"Load Temporary Add-on...\", choose " << dir
        << "/manifest.json\n"
        << "Then `umf-provider browser status` lists the browser while a provider runs.\n";
    return kOk;
}

int run_status(const cli::Args& a, std::ostream& out, std::ostream& err) {
    const ControlAnswer answer = ask_running_provider(running_provider_port(a).value_or(kDefaultPort), {{"cmd", "browsers"}}, err);
    if (answer.exit != kOk) return answer.exit;
    if (has_flag(a, "json"))
        out << answer.text << "\n";
    else
        out << browser_status_text(answer.json.value("browsers", nlohmann::json::array()));
    return kOk;
}

}  // namespace

int run_browser(const cli::Args& a, std::ostream& out, std::ostream& err) {
    if (a.positional.size() != 1) throw UsageError("browser takes one word: install or status");
    const std::string& word = a.positional.front();
    if (word == "install") {
        if (get(a, "port") || has_flag(a, "json")) throw UsageError("--port and --json go with browser status");
        return run_install(a, out, err);
    }
    if (word == "status") {
        if (get(a, "host") || get(a, "prefix") || has_flag(a, "system"))
            throw UsageError("--host, --prefix and --system go with browser install");
        return run_status(a, out, err);
    }
    throw UsageError("browser takes one word: install or status, not \"" + word + "\"");
}

}  // namespace umf::provider
