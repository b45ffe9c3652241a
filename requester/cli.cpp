#include "cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace umf::requester {

namespace {

bool contains(const std::vector<std::string>& list, const std::string& s) {
    return std::find(list.begin(), list.end(), s) != list.end();
}

// The whole of `text` as a finite number, or nothing.
std::optional<double> to_number(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(x)) return std::nullopt;
    return x;
}

}  // namespace

bool Args::has_flag(const std::string& name) const { return contains(flags, name); }

std::optional<std::string> Args::get(const std::string& name) const {
    for (const auto& [n, v] : named)
        if (n == name) return v;
    return std::nullopt;
}

Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                const std::vector<std::string>& flags) {
    Args a;
    bool only_files = false;
    for (int i = first; i < argc; ++i) {
        const std::string s = argv[i];
        if (only_files || s.rfind("--", 0) != 0) {
            a.positional.push_back(s);
            continue;
        }
        if (s == "--") {
            only_files = true;
            continue;
        }
        std::string name = s.substr(2);
        std::optional<std::string> value;
        if (auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name.resize(eq);
        }
        if (a.get(name) || a.has_flag(name)) throw UsageError("--" + name + " is given twice");
        if (contains(flags, name)) {
            if (value) throw UsageError("--" + name + " takes no value");
            a.flags.push_back(name);
            continue;
        }
        if (!contains(options, name)) throw UsageError("unknown option --" + name);
        if (!value) {
            if (i + 1 >= argc) throw UsageError("--" + name + " needs a value");
            value = argv[++i];
        }
        a.named.emplace_back(name, *value);
    }
    return a;
}

double parse_seconds(const std::string& text) {
    const auto s = to_number(text);
    if (!s || *s <= 0 || *s > 86400)
        throw UsageError("--timeout must be a number of seconds within (0, 86400], not '" + text + "'");
    return *s;
}

std::pair<double, double> parse_point(const std::string& option, const std::string& text) {
    const auto comma = text.find(',');
    if (comma != std::string::npos) {
        auto x = to_number(text.substr(0, comma));
        auto y = to_number(text.substr(comma + 1));
        if (x && y) return {*x, *y};
    }
    throw UsageError("--" + option + " must be two numbers X,Y, not '" + text + "'");
}

}  // namespace umf::requester
