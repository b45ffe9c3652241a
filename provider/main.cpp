// umf-provider: serve the field's content to requesters over a TLS WebSocket.
#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <pthread.h>
#include <signal.h>

#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/args.hpp"
#include "server/config_dir.hpp"
#include "server/pairing.hpp"
#include "server/server.hpp"
#include "server/service.hpp"
#include "server/tls_identity.hpp"

namespace {

using namespace umf::provider;

enum Exit {
    kOk = 0,
    kUsage = 2,
    kConfigError = 3,  // the configuration directory, the identity or the token cannot be read or written
    kServeError = 4,   // cannot listen, or the field cannot be loaded
};

constexpr unsigned short kDefaultPort = 47470;

const char* kUsageText = R"(umf-provider: show a marker field and serve what it points at

usage:
  umf-provider serve [--port P] [--bind ADDR] [--host HOST] [--config-dir DIR]
  umf-provider pair [--port P] [--host HOST] [--config-dir DIR] [--rotate]
  umf-provider --help

serve   listens for requesters on wss://ADDR:P/ws (default 127.0.0.1, port 47470;
        port 0 picks a free one), prints the pairing URL and serves until
        SIGINT or SIGTERM, then closes every session and exits.
pair    prints the pairing URL; --rotate makes a new token first, which
        unpairs every requester (a running server keeps the old token
        until it restarts).

--config-dir  where the TLS identity and the pairing token are kept
              (default $XDG_CONFIG_HOME/umf, else ~/.config/umf); made on first use.
--host        the host name or address put in the pairing URL (default: the
              bind address, or this machine's first non-loopback IPv4 address
              when binding to all addresses).

exit codes: 0 success; 2 wrong usage; 3 the configuration directory, TLS
            identity or token could not be read or written; 4 the server could
            not start.
)";

using umf::cli::Args;
using umf::cli::get;
using umf::cli::has_flag;
using umf::cli::UsageError;

// The tools' arguments (cli/args.hpp), without words: every argument here is
// an option or a flag.
Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                const std::vector<std::string>& flags) {
    Args a = umf::cli::parse_args(argc, argv, first, flags);
    umf::cli::reject_unknown(a, options);
    if (!a.positional.empty()) throw UsageError("unexpected argument " + a.positional.front());
    return a;
}

unsigned short port_option(const Args& a) {
    auto v = get(a, "port");
    if (!v) return kDefaultPort;
    return static_cast<unsigned short>(umf::cli::to_integer("port", *v, 0, 65535));
}

std::filesystem::path config_dir_option(const Args& a) {
    if (auto v = get(a, "config-dir")) {
        if (v->empty()) throw UsageError("--config-dir needs a directory");
        return *v;
    }
    return default_config_dir();
}

// The first up, non-loopback IPv4 address, or nullopt.
std::optional<std::string> first_lan_address() {
    ifaddrs* list = nullptr;
    if (getifaddrs(&list) != 0) return std::nullopt;
    std::optional<std::string> found;
    for (ifaddrs* i = list; i && !found; i = i->ifa_next) {
        if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET || !(i->ifa_flags & IFF_UP) ||
            (i->ifa_flags & IFF_LOOPBACK))
            continue;
        char text[INET_ADDRSTRLEN] = {};
        if (inet_ntop(AF_INET, &reinterpret_cast<sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof text))
            found = text;
    }
    freeifaddrs(list);
    return found;
}

std::string url_host(const Args& a, const std::string& bind) {
    if (auto h = get(a, "host")) {
        if (h->empty()) throw UsageError("--host needs a value");
        return *h;
    }
    if (bind == "0.0.0.0" || bind == "::") return first_lan_address().value_or("localhost");
    return bind;
}

int serve(const Args& a) {
    const unsigned short port = port_option(a);
    const std::string bind = get(a, "bind").value_or("127.0.0.1");
    const std::string host = url_host(a, bind);
    const auto dir = config_dir_option(a);

    TlsIdentity identity;
    std::string token;
    try {
        identity = load_or_create_tls_identity(dir);
        token = load_or_create_token(dir);
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }

    // SIGINT and SIGTERM are taken with sigwait below; blocked before any
    // thread starts, so none of the server's threads receives them.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);

    std::unique_ptr<Server> server;
    try {
        auto service = std::make_shared<const Service>(default_service_config(), token);
        ServerOptions options;
        options.bind_address = bind;
        options.port = port;
        options.threads = 2;
        server = std::make_unique<Server>(service, identity, options);
        server->start();
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kServeError;
    }

    std::cout << "umf-provider: listening on wss://" << (bind.find(':') != std::string::npos ? "[" + bind + "]" : bind)
              << ":" << server->port() << "/ws\n"
              << "pairing URL: " << pairing_url(host, server->port(), token, identity.fingerprint) << "\n"
              << "certificate fingerprint (SHA-256): " << identity.fingerprint << "\n"
              << std::flush;

    int received = 0;
    sigwait(&signals, &received);
    std::cerr << "umf-provider: " << (received == SIGINT ? "SIGINT" : "SIGTERM") << ", closing sessions\n";
    server->stop();
    std::cerr << "umf-provider: stopped\n";
    return kOk;
}

int pair(const Args& a) {
    const unsigned short port = port_option(a);
    const std::string host = url_host(a, "127.0.0.1");
    const auto dir = config_dir_option(a);
    try {
        const TlsIdentity identity = load_or_create_tls_identity(dir);
        const std::string token = load_or_create_token(dir, has_flag(a, "rotate"));
        std::cout << pairing_url(host, port, token, identity.fingerprint) << "\n";
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }
    return kOk;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << kUsageText;
        return kUsage;
    }
    const std::string command = argv[1];
    if (command == "--help" || command == "-h" || command == "help") {
        std::cout << kUsageText;
        return kOk;
    }
    try {
        for (int i = 2; i < argc; ++i)
            if (std::strcmp(argv[i], "--help") == 0) {
                std::cout << kUsageText;
                return kOk;
            }
        if (command == "serve")
            return serve(parse_args(argc, argv, 2, {"port", "bind", "host", "config-dir"}, {}));
        if (command == "pair") return pair(parse_args(argc, argv, 2, {"port", "host", "config-dir"}, {"rotate"}));
        throw UsageError("unknown command " + command);
    } catch (const UsageError& e) {
        std::cerr << "umf-provider: " << e.what() << "\n\n" << kUsageText;
        return kUsage;
    } catch (const ConfigError& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    }
}
