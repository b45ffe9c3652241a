// Options several umf-provider commands share.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shared/cli/args.hpp"

namespace umf::provider {

inline constexpr unsigned short kDefaultPort = 47470;

// Exit codes of every umf-provider command.
enum ProviderExit {
    kOk = 0,
    kUsage = 2,
    kConfigError = 3,  // the configuration directory, identity, token, board or an input cannot be read or written
    kServeError = 4,   // cannot listen, or the field cannot be loaded; the provider is not running (share)
};

// The tools' arguments (cli/args.hpp) with only the given options and flags;
// positional arguments allowed up to max_positional.
cli::Args parse_command_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                             const std::vector<std::string>& flags, std::size_t max_positional = 0);

unsigned short port_option(const cli::Args& a);
std::filesystem::path config_dir_option(const cli::Args& a);
// The host name or address put in the pairing URL: --host, else the bind
// address, or this machine's first non-loopback IPv4 address when binding to
// all addresses.
std::string url_host(const cli::Args& a, const std::string& bind);

// True for an address or name of this machine alone (127.0.0.1, ::1,
// localhost): a provider bound there serves no phone, so it announces
// nothing and its pairing URL names no .local name.
bool is_loopback(const std::string& host);

// "https://HOST:PORT", an IPv6 address in brackets.
std::string https_origin(const std::string& host, unsigned short port);

// "1920x1080" -> {1920, 1080}; UsageError otherwise.
std::pair<int, int> screen_size_option(const cli::Args& a, const std::string& name, std::pair<int, int> fallback);

}  // namespace umf::provider
