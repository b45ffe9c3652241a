// The umf GNOME Shell extension as the provider knows it: its names on the
// session bus (extension/org.umf.Shell1.xml) and its two built forms, held in
// the provider (generated from extension/ at build time).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace umf::provider {

// Set once, in desktop/gnome/CMakeLists.txt.
inline constexpr std::string_view kGnomeExtensionUuid = UMF_GNOME_EXTENSION_UUID;
inline constexpr const char* kGnomeShellBusName = "org.umf.Shell1";
inline constexpr const char* kGnomeShellObjectPath = "/org/umf/Shell1";
inline constexpr const char* kGnomeShellInterface = "org.umf.Shell1";
// The interface version this provider speaks (Version()'s api).
inline constexpr unsigned kGnomeShellApi = 2;

enum class GnomeExtensionForm {
    legacy,  // GNOME 43-44: imports.* and init()
    module,  // GNOME 45 and later: ES modules
};

struct GnomeExtensionFile {
    GnomeExtensionForm form;
    std::string_view name;  // within the extension's folder
    std::string_view text;
};

std::vector<GnomeExtensionFile> gnome_extension_files(GnomeExtensionForm form);

// The shell's major version from `gnome-shell --version`'s "GNOME Shell 43.9"
// or the ShellVersion property's "45.rc"; nullopt for anything else.
std::optional<int> gnome_shell_major(std::string_view version_text);

// The form a shell of that major version loads; nullopt before 43.
std::optional<GnomeExtensionForm> gnome_extension_form_for(int shell_major);

}  // namespace umf::provider
