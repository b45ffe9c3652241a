// Command-line arguments as the project's tools take them: words, options
// with a value (`--name V` or `--name=V`) and flags (`--name`), with the
// usage errors they raise. Shared by umf-field and umf-provider.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace umf::cli {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Args {
    std::vector<std::string> positional;
    std::map<std::string, std::string> named;
    std::vector<std::string> flags;
};

// argv[first..]: words not starting with "--" are positional; the names in
// `known_flags` take no value, every other "--name" takes one.
Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& known_flags);

// Throws for a named option outside `allowed`.
void reject_unknown(const Args& a, const std::vector<std::string>& allowed);

bool has_flag(const Args& a, const std::string& flag);
std::optional<std::string> get(const Args& a, const std::string& name);

// The option's value as an integer or number within [lo, hi], or a
// UsageError naming the option.
long long to_integer(const std::string& name, const std::string& v, long long lo, long long hi);
double to_number(const std::string& name, const std::string& v, double lo, double hi);

}  // namespace umf::cli
