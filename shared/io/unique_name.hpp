// The names a received file may take when its own is already used in the
// directory: "report.pdf", then "report (1).pdf", "report (2).pdf"... as
// browsers do, so neither a grab (the requester) nor a put (the provider)
// ever replaces a file the user already has.
// Header-only and free of I/O, so the tests check it directly.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace umf::io {

// Longest file name most Linux file systems take, in bytes.
inline constexpr std::size_t kMaxStoredNameBytes = 255;

namespace unique_name_detail {

// The longest prefix of s within `bytes` bytes that does not cut a UTF-8
// character in two.
inline std::string_view clip_utf8(std::string_view s, std::size_t bytes) {
    if (s.size() <= bytes) return s;
    std::size_t end = bytes;
    while (end > 0 && (static_cast<unsigned char>(s[end]) & 0xC0) == 0x80) --end;
    return s.substr(0, end);
}

}  // namespace unique_name_detail

// Where the extension starts: the last '.', unless the name is hidden
// (".bashrc" is all stem) or the dot ends the name ("notes." has no
// extension). Compound extensions like ".tar.gz" keep only their last part:
// "a.tar (1).gz" is ugly but still opens.
inline std::size_t extension_start(std::string_view name) {
    const auto dot = name.rfind('.');
    if (dot == std::string_view::npos || dot == 0 || dot + 1 == name.size()) return name.size();
    // "..hidden" or "...": every character before the dot is a dot.
    if (name.find_first_not_of('.') >= dot) return name.size();
    return dot;
}

// name for n == 0; "stem (n).ext" for n > 0, the stem shortened (at a
// character boundary) where the result would exceed kMaxStoredNameBytes.
inline std::string numbered_name(std::string_view name, int n) {
    if (n <= 0) return std::string(name);
    std::size_t ext_at = extension_start(name);
    std::string_view ext = name.substr(ext_at);
    const std::string suffix = " (" + std::to_string(n) + ")";
    // An extension so long it leaves no room for the number counts as stem.
    if (ext.size() + suffix.size() + 1 > kMaxStoredNameBytes) {
        ext_at = name.size();
        ext = {};
    }
    const std::size_t room = kMaxStoredNameBytes - suffix.size() - ext.size();
    const std::string_view stem = unique_name_detail::clip_utf8(name.substr(0, ext_at), room);
    return std::string(stem) + suffix + std::string(ext);
}

}  // namespace umf::io
