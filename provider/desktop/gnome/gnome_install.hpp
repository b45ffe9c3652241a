// `umf-provider gnome install`: puts the umf Shell extension where GNOME
// Shell looks for a user's extensions, in the form the running shell loads,
// and enables it. GNOME on Wayland reads new extensions only at login.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

#include "provider/desktop/gnome/gnome_extension.hpp"

namespace umf::provider {

// $XDG_DATA_HOME/gnome-shell/extensions, else ~/.local/share/...; empty
// when neither is set.
std::filesystem::path gnome_user_extensions_folder();

// Writes the form's files into `extensions_folder`/UUID (made when
// missing, older files replaced); the extension's folder. Throws
// std::runtime_error when a file cannot be written.
std::filesystem::path install_gnome_extension(const std::filesystem::path& extensions_folder, GnomeExtensionForm form);

// The value of org.gnome.shell enabled-extensions (GVariant text, "@as []"
// or "['a', 'b']") with `uuid` added once; the same text when it is there.
std::string with_extension_enabled(const std::string& gvariant_list, const std::string& uuid);

// The whole command: finds the shell's version (gnome-shell --version),
// installs, enables (gnome-extensions enable, else the gsettings key), and
// says what is left to do. 0 on success.
int run_gnome_install(std::ostream& out, std::ostream& err);

}  // namespace umf::provider
