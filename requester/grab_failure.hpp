// Why a grab ended without content: the code that goes into the JSON line
// ("connection", "certificate", "unauthorized", "not_found_in_view", ...),
// a message for people, and the exit code (cli.hpp).
#pragma once

#include <stdexcept>
#include <string>

namespace umf::requester {

struct GrabFailure : std::runtime_error {
    GrabFailure(std::string code_, const std::string& message, int exit_code_)
        : std::runtime_error(message), code(std::move(code_)), exit_code(exit_code_) {}
    std::string code;
    int exit_code;
};

}  // namespace umf::requester
