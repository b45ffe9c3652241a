#include "requester/cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "shared/overlay/preset.hpp"

namespace umf::requester {

namespace {

// The whole of `text` as a finite number, or nothing.
std::optional<double> to_number(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(x)) return std::nullopt;
    return x;
}

}  // namespace

double parse_seconds(const std::string& text) {
    const auto s = to_number(text);
    if (!s || *s <= 0 || *s > 86400)
        throw UsageError("--timeout must be a number of seconds within (0, 86400], not '" + text + "'");
    return *s;
}

double parse_pulse_period(const std::string& text) {
    const auto s = to_number(text);
    if (!s || *s < overlay::kMinPeriodS || *s > overlay::kMaxPeriodS) {
        std::ostringstream m;
        m << "--pulse-period must be a number of seconds within [" << overlay::kMinPeriodS << ", "
          << overlay::kMaxPeriodS << "], not '" << text << "'";
        throw UsageError(m.str());
    }
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
