// umf-provider: show a marker field and serve what it points at. The command
// line is read in command_line.hpp and the commands live in commands/; main
// turns what they throw into the exit codes of `umf-provider --help`.
#include <cstring>
#include <exception>
#include <iostream>

#include "provider/command_line.hpp"
#include "provider/commands/common_options.hpp"
#include "provider/common/config_dir.hpp"
#include "shared/cli/args.hpp"

int main(int argc, char** argv) {
    using namespace umf::provider;
    for (int i = 1; i < argc; ++i)
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0 ||
            (i == 1 && std::strcmp(argv[i], "help") == 0)) {
            std::cout << kProviderUsage;
            return kOk;
        }
    try {
        return run_command_line(argc, argv);
    } catch (const umf::cli::UsageError& e) {
        std::cerr << "umf-provider: " << e.what() << "\n\n" << kProviderUsage;
        return kUsage;
    } catch (const ConfigError& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kConfigError;
    } catch (const std::exception& e) {
        std::cerr << "umf-provider: " << e.what() << "\n";
        return kServeError;
    }
}
