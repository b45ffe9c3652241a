// umf-provider compose: the screen exactly as the provider would show it at a
// moment of the pulse, as a PNG, and where the field lies on it, as JSON.
// Tests and the camera simulator photograph it; people use it to see what a
// preset looks like over their own screenshot or board.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shared/cli/args.hpp"

namespace umf::provider {

extern const char* const kComposeUsage;

// Exit codes besides 0: wrong usage is thrown as umf::cli::UsageError.
inline constexpr int kComposeInputError = 3;   // content, board, presets or field cannot be read or are invalid
inline constexpr int kComposeOutputError = 4;  // OUT.png or MAP.json cannot be written

// The options and flags of `umf-provider compose` (with --config-dir).
std::vector<std::string> compose_options();
std::vector<std::string> compose_flags();

// `args` holds the options after "compose", parsed against those.
// Presets are the built-ins and, when config_dir/presets.json exists, the
// user's own (taking precedence over a built-in of the same name). Needs a
// QGuiApplication (screen/gui_application.hpp). Reports errors other than
// usage on std::cerr and returns their exit code; 0 on success.
int run_compose(const umf::cli::Args& args, const std::filesystem::path& config_dir);

}  // namespace umf::provider
