#include "cli/args.hpp"

namespace umf::cli {

Args parse_args(int argc, char** argv, int first, const std::vector<std::string>& known_flags) {
    Args a;
    for (int i = first; i < argc; ++i) {
        std::string s = argv[i];
        if (s.rfind("--", 0) != 0 || s.size() == 2) {
            a.positional.push_back(s);
            continue;
        }
        std::string name = s.substr(2);
        if (auto eq = name.find('='); eq != std::string::npos) {
            a.named[name.substr(0, eq)] = name.substr(eq + 1);
            continue;
        }
        bool is_flag = false;
        for (const auto& f : known_flags) is_flag |= f == name;
        if (is_flag) {
            a.flags.push_back(name);
            continue;
        }
        if (i + 1 >= argc) throw UsageError("--" + name + " needs a value");
        a.named[name] = argv[++i];
    }
    return a;
}

void reject_unknown(const Args& a, const std::vector<std::string>& allowed) {
    for (const auto& [name, value] : a.named) {
        bool ok = false;
        for (const auto& n : allowed) ok |= n == name;
        if (!ok) throw UsageError("unknown option --" + name);
    }
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
