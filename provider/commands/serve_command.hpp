// `umf-provider [serve]`: the provider itself. Headless (no display, or
// --headless) it shows a board on a virtual screen, the built-in demo board
// unless --board names one; on a desktop it serves what lies under the point.
#pragma once

#include "cli/args.hpp"

namespace umf::provider {

extern const char* const kServeOptions[];
extern const char* const kServeFlags[];

// Needs a QGuiApplication (main makes it). Returns the exit code after
// SIGINT or SIGTERM.
int run_serve(const cli::Args& args);

}  // namespace umf::provider
