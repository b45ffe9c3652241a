#include "provider/desktop/desktop_entry.hpp"

#include <string_view>

namespace umf::provider {

// Made by provider/CMakeLists.txt from umf-provider.desktop.in, so the
// packaged file and the ones written at run time cannot drift apart.
const char* provider_desktop_entry_template();

namespace {

// The Desktop Entry Specification's quoting of an Exec argument: a path with
// a space or a reserved character goes in double quotes, with a backslash
// before each ", `, $ and backslash, and a literal % doubled. The value's own escaping comes after
// (applied before the quoting when read): each backslash doubled.
std::string exec_argument(const std::string& path) {
    std::string plain;
    bool quote = false;
    for (char c : path) {
        if (c == '%') plain += '%';
        if (std::string_view(" \t\n\"'\\><~|&;$*?#()`").find(c) != std::string_view::npos) quote = true;
        plain += c;
    }
    if (!quote) return plain;
    std::string quoted = "\"";
    for (char c : plain) {
        if (c == '"' || c == '`' || c == '$') quoted += "\\\\";
        if (c == '\\') quoted += "\\\\\\";
        quoted += c;
    }
    return quoted + '"';
}

}  // namespace

std::string provider_desktop_entry(const std::string& executable) {
    std::string entry = provider_desktop_entry_template();
    const std::string mark = "@EXEC@", exec = exec_argument(executable);
    for (auto at = entry.find(mark); at != std::string::npos; at = entry.find(mark, at + exec.size()))
        entry.replace(at, mark.size(), exec);
    return entry;
}

}  // namespace umf::provider
