#include "provider/commands/common_options.hpp"

#include <optional>

#include "provider/common/config_dir.hpp"
#include "provider/trust/serving_names.hpp"

namespace umf::provider {

using cli::Args;
using cli::get;
using cli::UsageError;

Args parse_command_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                        const std::vector<std::string>& flags, std::size_t max_positional) {
    Args a = cli::parse_args(argc, argv, first, options, flags);
    if (a.positional.size() > max_positional)
        throw UsageError("unexpected argument " + a.positional[max_positional]);
    return a;
}

unsigned short port_option(const Args& a) {
    auto v = get(a, "port");
    if (!v) return kDefaultPort;
    return static_cast<unsigned short>(cli::to_integer("port", *v, 0, 65535));
}

std::filesystem::path config_dir_option(const Args& a) {
    if (auto v = get(a, "config-dir")) {
        if (v->empty()) throw UsageError("--config-dir needs a directory");
        return *v;
    }
    return default_config_dir();
}

namespace {

// The first up, non-loopback IPv4 address, a private one (which the
// screen's certificate names) before any other; nullopt when there is none.
std::optional<std::string> first_lan_address() {
    std::optional<std::string> other;
    for (const auto& address : current_addresses()) {
        if (address.find(':') != std::string::npos || address.rfind("127.", 0) == 0) continue;
        if (address_may_be_vouched(address)) return address;
        if (!other) other = address;
    }
    return other;
}

}  // namespace

std::string url_host(const Args& a, const std::string& bind) {
    if (auto h = get(a, "host")) {
        if (h->empty()) throw UsageError("--host needs a value");
        return *h;
    }
    if (bind == "0.0.0.0" || bind == "::") return first_lan_address().value_or("localhost");
    return bind;
}

bool is_loopback(const std::string& host) { return host == "127.0.0.1" || host == "::1" || host == "localhost"; }

std::string https_origin(const std::string& host, unsigned short port) {
    return "https://" + (host.find(':') != std::string::npos ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

std::pair<int, int> screen_size_option(const Args& a, const std::string& name, std::pair<int, int> fallback) {
    auto v = get(a, name);
    if (!v) return fallback;
    const auto x = v->find('x');
    if (x == std::string::npos) throw UsageError("--" + name + " takes WIDTHxHEIGHT, for example 1920x1080");
    return {static_cast<int>(cli::to_integer(name + " width", v->substr(0, x), 64, 16384)),
            static_cast<int>(cli::to_integer(name + " height", v->substr(x + 1), 64, 16384))};
}

}  // namespace umf::provider
