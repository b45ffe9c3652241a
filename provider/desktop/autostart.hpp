// Starting the provider at login: the XDG autostart entry that the tray's
// "Start at login" and `umf-provider autostart on|off` write and remove.
// Desktops that follow the XDG Autostart Specification (GNOME, KDE Plasma,
// Xfce, LXQt, and sway or others through a helper) start every entry in
// $XDG_CONFIG_HOME/autostart at login.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>

namespace umf::provider {

// $XDG_CONFIG_HOME/autostart/umf-provider.desktop, else
// ~/.config/autostart/...; empty when neither is set.
std::filesystem::path autostart_entry_path();

// The entry is there and not Hidden=true (how a user's copy of a system
// entry turns it off, by the specification).
bool autostart_enabled(const std::filesystem::path& entry);

// On: writes the provider's desktop entry naming `executable` (folder made
// when missing). Off: removes the entry. Throws std::runtime_error naming
// the file when it cannot be written or removed.
void set_autostart(const std::filesystem::path& entry, bool on, const std::filesystem::path& executable);
// The same for the running program; throws std::runtime_error also when it
// cannot tell where it is.
void set_autostart_for_this_program(const std::filesystem::path& entry, bool on);

// `umf-provider autostart [on|off]`: switches it for this program (nothing:
// leaves it) and says whether the provider starts at login. 0 on success, 3
// when the entry cannot be written.
int run_autostart(std::optional<bool> on, std::ostream& out, std::ostream& err);

}  // namespace umf::provider
