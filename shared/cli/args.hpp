// Command-line arguments as the project's programs take them (umf-field,
// umf-provider, umf-requester): words, options with a value (`--name V` or
// `--name=V`) and flags (`--name`), with the usage errors they raise.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace umf::cli {

// Wrong usage: each program prints it with a pointer to its --help.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Args {
    std::vector<std::string> positional;       // in the order given
    std::map<std::string, std::string> named;  // without the leading "--"
    std::vector<std::string> flags;
};

// Parses argv[first..]: "--name value" and "--name=value" for the names in
// `options`, "--name" alone for those in `flags`, every other word (and
// everything after a lone "--") as positional. Throws UsageError for a name
// in neither list, one given twice, an option without its value or a flag
// with one.
Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                const std::vector<std::string>& flags);

bool has_flag(const Args& a, const std::string& flag);
std::optional<std::string> get(const Args& a, const std::string& name);

// The option's value as an integer or number within [lo, hi], or a
// UsageError naming the option.
long long to_integer(const std::string& name, const std::string& v, long long lo, long long hi);
double to_number(const std::string& name, const std::string& v, double lo, double hi);

}  // namespace umf::cli
