// The provider's command line: its help and the command each word runs.
#pragma once

namespace umf::provider {

// What --help prints.
extern const char* const kProviderUsage;

// Runs the command the arguments name (serve when the first one is an
// option) and returns its exit code (ProviderExit). Throws cli::UsageError
// for a command line against the rules, ConfigError, and what the command
// throws.
int run_command_line(int argc, char** argv);

}  // namespace umf::provider
