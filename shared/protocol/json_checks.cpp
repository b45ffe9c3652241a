#include "shared/protocol/json_checks.hpp"

#include <cmath>
#include <cstdio>

namespace umf::protocol {

namespace {

using nlohmann::json;

// Length of the valid UTF-8 sequence at s[i], or 0 when the bytes there are
// not one (overlong forms, surrogates and code points above U+10FFFF included).
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char b0 = byte(i);
    if (b0 < 0x80) return 1;
    std::size_t n;
    unsigned char lo = 0x80, hi = 0xbf;  // allowed range of the second byte
    if (b0 >= 0xc2 && b0 <= 0xdf) {
        n = 2;
    } else if (b0 >= 0xe0 && b0 <= 0xef) {
        n = 3;
        if (b0 == 0xe0) lo = 0xa0;  // overlong
        if (b0 == 0xed) hi = 0x9f;  // surrogates
    } else if (b0 >= 0xf0 && b0 <= 0xf4) {
        n = 4;
        if (b0 == 0xf0) lo = 0x90;  // overlong
        if (b0 == 0xf4) hi = 0x8f;  // above U+10FFFF
    } else {
        return 0;
    }
    if (i + n > s.size()) return 0;
    if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
    return n;
}

std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

std::string describe_range(double lo, double hi) { return format_number(lo) + ".." + format_number(hi); }

std::string describe_integer_range(std::int64_t lo, std::int64_t hi) {
    return std::to_string(lo) + ".." + std::to_string(hi);
}

// The JSON value in a problem message, short: received text is not echoed at length.
std::string show(const json& v) {
    if (v.is_number()) {
        auto d = finite_number(v);
        if (d) return v.is_number_float() ? format_number(*d) : v.dump();
        return "a non-finite number";
    }
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return "null";
}

}  // namespace

bool is_valid_utf8(std::string_view s) {
    for (std::size_t i = 0; i < s.size();) {
        std::size_t n = utf8_sequence_length(s, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

bool has_control_chars(std::string_view s) {
    for (char c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
    return false;
}

bool is_lower_hex(std::string_view s) {
    for (char c : s)
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
    return true;
}

std::string clip_text(std::string_view s, std::size_t max_bytes) {
    static constexpr std::string_view kReplacement = "\xef\xbf\xbd";
    std::string out;
    out.reserve(std::min(s.size(), max_bytes));
    for (std::size_t i = 0; i < s.size();) {
        std::size_t n = utf8_sequence_length(s, i);
        std::string_view piece = n ? s.substr(i, n) : kReplacement;
        if (out.size() + piece.size() > max_bytes) break;
        out += piece;
        i += n ? n : 1;
    }
    return out;
}

std::optional<double> finite_number(const json& v) {
    if (!v.is_number()) return std::nullopt;
    double d = v.get<double>();
    if (!std::isfinite(d)) return std::nullopt;
    return d;
}

std::optional<std::int64_t> integer_in(const json& v, std::int64_t lo, std::int64_t hi) {
    std::int64_t n;
    if (v.is_number_unsigned()) {
        auto u = v.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(INT64_MAX)) return std::nullopt;
        n = static_cast<std::int64_t>(u);
    } else if (v.is_number_integer()) {
        n = v.get<std::int64_t>();
    } else {
        return std::nullopt;
    }
    if (n < lo || n > hi) return std::nullopt;
    return n;
}

MemberReader::MemberReader(const json& object, std::string path) : object_(&object), path_(std::move(path)) {
    if (!object.is_object()) fail((path_.empty() ? std::string("the message") : "\"" + path_ + "\"") + " must be a JSON object");
}

void MemberReader::fail(const std::string& what) {
    if (problem_.empty()) problem_ = what;
}

std::string MemberReader::name(std::string_view key) const {
    std::string n = "\"";
    if (!path_.empty()) n += path_ + ".";
    n += key;
    return n + "\"";
}

const json* MemberReader::get(const char* key) const {
    if (!object_->is_object()) return nullptr;
    auto it = object_->find(key);
    if (it == object_->end() || it->is_null()) return nullptr;
    return &*it;
}

bool MemberReader::has(const char* key) const { return get(key) != nullptr; }

std::optional<std::string> MemberReader::optional_text(const char* key, std::size_t min_bytes,
                                                        std::size_t max_bytes) {
    const json* v = get(key);
    if (!ok() || !v) return std::nullopt;
    if (!v->is_string()) {
        fail(name(key) + " must be a string, not " + show(*v));
        return std::nullopt;
    }
    const auto& s = v->get_ref<const std::string&>();
    if (s.size() < min_bytes || s.size() > max_bytes) {
        std::string want = min_bytes == max_bytes ? std::to_string(max_bytes)
                           : min_bytes > 0        ? std::to_string(min_bytes) + " to " + std::to_string(max_bytes)
                                                  : "at most " + std::to_string(max_bytes);
        fail(name(key) + " must be " + want + " bytes long, not " + std::to_string(s.size()));
        return std::nullopt;
    }
    return s;
}

std::string MemberReader::text(const char* key, std::size_t min_bytes, std::size_t max_bytes) {
    if (ok() && !has(key)) fail("missing " + name(key));
    return optional_text(key, min_bytes, max_bytes).value_or(std::string());
}

std::optional<double> MemberReader::optional_number(const char* key, double lo, double hi) {
    const json* v = get(key);
    if (!ok() || !v) return std::nullopt;
    auto d = finite_number(*v);
    if (!d || *d < lo || *d > hi) {
        fail(name(key) + " must be a number " + describe_range(lo, hi) + ", not " + show(*v));
        return std::nullopt;
    }
    return d;
}

double MemberReader::number(const char* key, double lo, double hi) {
    if (ok() && !has(key)) fail("missing " + name(key));
    return optional_number(key, lo, hi).value_or(0.0);
}

std::optional<std::int64_t> MemberReader::optional_integer(const char* key, std::int64_t lo, std::int64_t hi) {
    const json* v = get(key);
    if (!ok() || !v) return std::nullopt;
    auto n = integer_in(*v, lo, hi);
    if (!n) fail(name(key) + " must be an integer " + describe_integer_range(lo, hi) + ", not " + show(*v));
    return n;
}

std::int64_t MemberReader::integer(const char* key, std::int64_t lo, std::int64_t hi) {
    if (ok() && !has(key)) fail("missing " + name(key));
    return optional_integer(key, lo, hi).value_or(0);
}

const json* MemberReader::object(const char* key) {
    const json* v = get(key);
    if (!ok()) return nullptr;
    if (!v) {
        fail("missing " + name(key));
        return nullptr;
    }
    if (!v->is_object()) {
        fail(name(key) + " must be an object, not " + show(*v));
        return nullptr;
    }
    return v;
}

const json* MemberReader::array(const char* key, std::size_t min_size, std::size_t max_size) {
    const json* v = get(key);
    if (!ok()) return nullptr;
    if (!v) {
        fail("missing " + name(key));
        return nullptr;
    }
    if (!v->is_array()) {
        fail(name(key) + " must be an array, not " + show(*v));
        return nullptr;
    }
    if (v->size() < min_size || v->size() > max_size) {
        fail(name(key) + " must have " + std::to_string(min_size) + " to " + std::to_string(max_size) +
             " entries, not " + std::to_string(v->size()));
        return nullptr;
    }
    return v;
}

}  // namespace umf::protocol
