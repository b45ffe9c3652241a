#include "commands/control_client.hpp"

#include "commands/common_options.hpp"
#include "put/put_text.hpp"
#include "server/control_socket.hpp"

namespace umf::provider {

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
