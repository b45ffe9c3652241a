#include "shared/cli/args.hpp"

namespace umf::cli {

namespace {

bool contains(const std::vector<std::string>& list, const std::string& s) {
    for (const auto& x : list)
        if (x == s) return true;
    return false;
}

}  // namespace

Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& options,
                const std::vector<std::string>& flags) {
    Args a;
    bool only_words = false;
    for (int i = first; i < argc; ++i) {
        const std::string s = argv[i];
        if (only_words || s.rfind("--", 0) != 0) {
            a.positional.push_back(s);
            continue;
        }
        if (s == "--") {
            only_words = true;
            continue;
        }
        std::string name = s.substr(2);
        std::optional<std::string> value;
        if (auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name.resize(eq);
        }
        if (a.named.count(name) || has_flag(a, name)) throw UsageError("--" + name + " is given twice");
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
        a.named.emplace(name, *value);
    }
    return a;
}

bool has_flag(const Args& a, const std::string& flag) {
    for (const auto& x : a.flags)
        if (x == flag) return true;
    return false;
}

std::optional<std::string> get(const Args& a, const std::string& name) {
    auto it = a.named.find(name);
    if (it == a.named.end()) return std::nullopt;
    return it->second;
}

long long to_integer(const std::string& name, const std::string& v, long long lo, long long hi) {
    std::size_t used = 0;
    long long x = 0;
    try {
        x = std::stoll(v, &used);
    } catch (...) {
        used = 0;
    }
    if (used != v.size() || v.empty()) throw UsageError("--" + name + " must be an integer, not '" + v + "'");
    if (x < lo || x > hi)
        throw UsageError("--" + name + " must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return x;
}

double to_number(const std::string& name, const std::string& v, double lo, double hi) {
    std::size_t used = 0;
    double x = 0;
    try {
        x = std::stod(v, &used);
    } catch (...) {
        used = 0;
    }
    if (used != v.size() || v.empty()) throw UsageError("--" + name + " must be a number, not '" + v + "'");
    if (!(x >= lo && x <= hi))
        throw UsageError("--" + name + " must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return x;
}

}  // namespace umf::cli
