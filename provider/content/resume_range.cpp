#include "provider/content/resume_range.hpp"

#include <charconv>
#include <optional>

namespace umf::provider {

namespace {

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

// Digits only, no sign, no overflow.
std::optional<std::uint64_t> number(std::string_view s) {
    if (s.empty()) return std::nullopt;
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    return value;
}

}  // namespace

std::string download_etag(std::string_view sha256) { return "\"sha256-" + std::string(sha256) + "\""; }

ResumeRange resume_range(std::string_view range, std::string_view if_range, std::string_view etag, std::uint64_t size) {
    const ResumeRange whole;
    range = trimmed(range);
    constexpr std::string_view kUnit = "bytes=";
    if (range.substr(0, kUnit.size()) != kUnit || size == 0) return whole;
    // If-Range with a date, or another validator: the file may have changed.
    if (!trimmed(if_range).empty() && trimmed(if_range) != etag) return whole;
    const std::string_view spec = trimmed(range.substr(kUnit.size()));
    const auto dash = spec.find('-');
    if (dash == std::string_view::npos || spec.find(',') != std::string_view::npos) return whole;
    const std::string_view first = trimmed(spec.substr(0, dash)), last = trimmed(spec.substr(dash + 1));
    if (first.empty()) {
        // bytes=-K: the last K bytes.
        const auto suffix = number(last);
        if (!suffix || *suffix == 0) return whole;
        return {ResumeRange::Kind::rest, *suffix >= size ? 0 : size - *suffix};
    }
    const auto from = number(first);
    if (!from) return whole;
    if (!last.empty()) {
        const auto to = number(last);
        if (!to || *to < *from || *to < size - 1) return whole;  // ends before the file does
    }
    if (*from >= size) return {ResumeRange::Kind::unsatisfiable, 0};
    return {ResumeRange::Kind::rest, *from};
}

}  // namespace umf::provider
