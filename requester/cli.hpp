// What every umf-requester command shares: exit codes, the usage error and
// the parsing of "--name value", "--name=value", flags and file arguments.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace umf::requester {

enum Exit {
    kOk = 0,         // the command ran; per-frame trouble is reported in its output
    kUsage = 2,      // wrong usage
    kInputError = 3,  // the field file, the video or the output could not be read or written;
                      // discover: built without Avahi
    kConnection = 4,  // grab: the provider could not be reached, its certificate or its replies were wrong;
                      // discover: the Avahi daemon could not be asked
    kNothing = 5      // grab: nothing was grabbed (no field in view, nothing at the point, refused);
                      // discover: no screen answered
};

// Wrong usage: main prints it with a pointer to --help and exits with kUsage.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A file or stream the command cannot work without: exits with kInputError.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Args {
    std::vector<std::string> positional;                       // in the order given
    std::vector<std::pair<std::string, std::string>> named;    // without the leading "--"
    std::vector<std::string> flags;

    bool has_flag(const std::string& name) const;
    std::optional<std::string> get(const std::string& name) const;
};

// Parses argv[first..]: "--name value" and "--name=value" for options,
// "--name" alone for the known flags, everything else (and everything after
// a lone "--") as positional. Throws UsageError for an option given twice, an
// option outside `options` or `flags`, or an option without its value.
Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                const std::vector<std::string>& flags);

// "X,Y" as two finite numbers; throws UsageError naming the option.
std::pair<double, double> parse_point(const std::string& option, const std::string& text);

// "--timeout S": a number of seconds within (0, 86400]; throws UsageError.
double parse_seconds(const std::string& text);

}  // namespace umf::requester
