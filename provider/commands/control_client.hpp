// What the commands that talk to a running provider (`puts`, `browser
// status`) share: one request on its control socket and the answer checked.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

namespace umf::provider {

struct ControlAnswer {
    int exit = 0;          // kOk when the provider said ok; else the command's exit code
    std::string text;      // the answer as it came
    nlohmann::json json;   // parsed, when exit is kOk
};

// Sends `request` to the provider on `port`. When none runs, it does not
// answer JSON, or it refuses, says why on `err` (provider text cleaned for a
// terminal) and returns kServeError or kConfigError.
ControlAnswer ask_running_provider(unsigned short port, const nlohmann::json& request, std::ostream& err);

}  // namespace umf::provider
