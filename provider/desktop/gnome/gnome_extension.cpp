#include "provider/desktop/gnome/gnome_extension.hpp"

#include <cctype>

namespace umf::provider {

std::optional<int> gnome_shell_major(std::string_view text) {
    constexpr std::string_view prefix = "GNOME Shell ";
    if (text.substr(0, prefix.size()) == prefix) text.remove_prefix(prefix.size());
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
    int major = 0;
    std::size_t digits = 0;
    for (; digits < text.size() && digits < 4 && std::isdigit(static_cast<unsigned char>(text[digits])); ++digits)
        major = major * 10 + (text[digits] - '0');
    if (digits == 0 || digits == 4) return std::nullopt;
    if (digits < text.size() && text[digits] != '.' && !std::isspace(static_cast<unsigned char>(text[digits])))
        return std::nullopt;
    return major;
}

std::optional<GnomeExtensionForm> gnome_extension_form_for(int shell_major) {
    if (shell_major < 43) return std::nullopt;
    return shell_major < 45 ? GnomeExtensionForm::legacy : GnomeExtensionForm::module;
}

}  // namespace umf::provider
