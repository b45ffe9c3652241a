// Readers for JSON that came from the other side of a connection. They never
// throw, whatever the input: a MemberReader keeps the first problem it finds,
// in words that name the member, and after a problem every read returns a
// default, so a parser reads all it needs and asks ok() once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace umf::protocol {

// Text checks; pure.
bool is_valid_utf8(std::string_view s);
// C0 controls (below U+0020) and DEL.
bool has_control_chars(std::string_view s);
bool is_lower_hex(std::string_view s);

// `s` as valid UTF-8 of at most `max_bytes`: each invalid byte becomes U+FFFD
// and the end is cut at a character boundary. For display text (titles,
// names, error messages), which is better shortened than refused.
std::string clip_text(std::string_view s, std::size_t max_bytes);

// A JSON number as a double, when it is one and finite; integers included.
std::optional<double> finite_number(const nlohmann::json& v);
// A JSON integer (not 1.0) within [lo, hi].
std::optional<std::int64_t> integer_in(const nlohmann::json& v, std::int64_t lo, std::int64_t hi);

// The largest integer a JavaScript number holds exactly (2^53 - 1): sizes and
// integer ids stay within it so the phone page reads them unchanged.
inline constexpr std::int64_t kMaxSafeInteger = 9'007'199'254'740'991;

class MemberReader {
public:
    // `path` prefixes member names in problems ("field.screens[2]"); empty at the top.
    explicit MemberReader(const nlohmann::json& object, std::string path = {});
    // The reader keeps a pointer to the object, so a temporary would dangle.
    explicit MemberReader(const nlohmann::json&& object, std::string path = {}) = delete;

    bool ok() const { return problem_.empty(); }
    const std::string& problem() const { return problem_; }
    // Records a problem found by the caller; the first one is kept.
    void fail(const std::string& what);
    // How problems name a member: "\"title\"", "\"field.screens[0].name\"".
    std::string name(std::string_view key) const;
    std::string path() const { return path_; }

    // Present and not null: null counts as absent, as JavaScript writes it for
    // undefined optional values.
    bool has(const char* key) const;
    const nlohmann::json* get(const char* key) const;

    std::string text(const char* key, std::size_t min_bytes, std::size_t max_bytes);
    std::optional<std::string> optional_text(const char* key, std::size_t min_bytes, std::size_t max_bytes);
    double number(const char* key, double lo, double hi);
    std::optional<double> optional_number(const char* key, double lo, double hi);
    std::int64_t integer(const char* key, std::int64_t lo, std::int64_t hi);
    std::optional<std::int64_t> optional_integer(const char* key, std::int64_t lo, std::int64_t hi);
    // A required member that must be an object or an array; nullptr after a problem.
    const nlohmann::json* object(const char* key);
    const nlohmann::json* array(const char* key, std::size_t min_size, std::size_t max_size);

private:
    const nlohmann::json* object_;
    std::string path_;
    std::string problem_;
};

}  // namespace umf::protocol
