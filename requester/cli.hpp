// What every umf-requester command shares: exit codes, the input error and
// the command line (shared/cli/args.hpp) with the values only it reads.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "shared/cli/args.hpp"

namespace umf::requester {

enum RequesterExit {
    kOk = 0,         // the command ran; per-frame trouble is reported in its output
    kUsage = 2,      // wrong usage
    kInputError = 3,  // the field file, the video or the output could not be read or written;
                      // discover: built without Avahi
    kConnection = 4,  // grab: the provider could not be reached, its certificate or its replies were wrong;
                      // discover: the Avahi daemon could not be asked
    kNothing = 5      // grab: nothing was grabbed (no field in view, nothing at the point, refused);
                      // discover: no screen answered
};

// A file or stream the command cannot work without: exits with kInputError.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The project's one parser (shared/cli/args.hpp): "--name value",
// "--name=value", the known flags and the words; UsageError makes main print
// it with a pointer to --help and exit with kUsage.
using cli::Args;
using cli::get;
using cli::has_flag;
using cli::parse_args;
using cli::UsageError;

// "--pulse-period S": a number of seconds within the presets' range
// (overlay::kMinPeriodS..kMaxPeriodS); throws UsageError.
double parse_pulse_period(const std::string& text);

// "X,Y" as two finite numbers; throws UsageError naming the option.
std::pair<double, double> parse_point(const std::string& option, const std::string& text);

// "--timeout S": a number of seconds within (0, 86400]; throws UsageError.
double parse_seconds(const std::string& text);

}  // namespace umf::requester
