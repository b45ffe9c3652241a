// What the commands that talk to a running provider (`puts`, `browser
// status`) share: one request on its control socket and the answer checked.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "shared/cli/args.hpp"

namespace umf::provider {

struct ControlAnswer {
    int exit = 0;          // kOk when the provider said ok; else the command's exit code
    std::string text;      // the answer as it came
    nlohmann::json json;   // parsed, when exit is kOk
};

// The port of the running provider a command talks to: --port when given;
// else the one provider of this user that runs, when exactly one does;
// nullopt when none runs (the commands then try the default port, and the
// request says that none runs). Several running: a UsageError naming them.
std::optional<unsigned short> running_provider_port(const cli::Args& a);

// A command line for the console's hints: `command` with " --port P" when
// P is not the default port.
std::string with_port(const std::string& command, unsigned short port);

// Sends `request` to the provider on `port`. When none runs, it does not
// answer JSON, or it refuses, says why on `err` (provider text cleaned for a
// terminal) and returns kServeError or kConfigError.
ControlAnswer ask_running_provider(unsigned short port, const nlohmann::json& request, std::ostream& err);

}  // namespace umf::provider
