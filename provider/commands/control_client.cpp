#include "provider/commands/control_client.hpp"

#include "provider/commands/common_options.hpp"
#include "provider/put/put_text.hpp"
#include "provider/service/control_socket.hpp"

namespace umf::provider {

std::optional<unsigned short> running_provider_port(const cli::Args& a) {
    if (cli::get(a, "port")) return port_option(a);
    const std::vector<unsigned short> ports = running_provider_ports();
    if (ports.size() == 1) return ports[0];
    if (ports.empty()) return std::nullopt;
    std::string list;
    for (std::size_t i = 0; i < ports.size(); ++i)
        list += (i == 0 ? "" : i + 1 == ports.size() ? " and " : ", ") + std::to_string(ports[i]);
    throw cli::UsageError("providers run on ports " + list + ": say which with --port");
}

std::string with_port(const std::string& command, unsigned short port) {
    return port == kDefaultPort ? command : command + " --port " + std::to_string(port);
}

ControlAnswer ask_running_provider(unsigned short port, const nlohmann::json& request, std::ostream& err) {
    using json = nlohmann::json;
    ControlAnswer answer;
    try {
        answer.text = control_request(control_socket_path(port), request.dump());
    } catch (const std::exception& e) {
        err << "umf-provider: " << e.what() << "\n";
        answer.exit = kServeError;
        return answer;
    }
    json parsed = json::parse(answer.text, nullptr, false);
    if (!parsed.is_object()) {
        err << "umf-provider: the provider answered something else than JSON: " << printable_text(answer.text) << "\n";
        answer.exit = kServeError;
    } else if (!parsed.value("ok", false)) {
        err << "umf-provider: " << printable_text(parsed.value("error", std::string("the provider refused"))) << "\n";
        answer.exit = kConfigError;
    } else {
        answer.json = std::move(parsed);
    }
    return answer;
}

}  // namespace umf::provider
