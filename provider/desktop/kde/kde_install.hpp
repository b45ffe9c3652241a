// `umf-provider kde install`: what KWin needs to let the provider take
// snapshots. KWin 5.27 answers org.kde.KWin.ScreenShot2 only to a program
// whose desktop file, found by the path of its executable, lists that
// interface under X-KDE-DBUS-Restricted-Interfaces (kwin_screenshot.hpp).
#pragma once

#include <filesystem>
#include <iosfwd>

namespace umf::provider {

// Writes umf-provider.desktop for `executable` into `applications` (made
// when missing); 0 on success, else 3 with the reason on `err`.
int install_kde_desktop_entry(const std::filesystem::path& executable, const std::filesystem::path& applications,
                              std::ostream& out, std::ostream& err);

// The running program into $XDG_DATA_HOME/applications (~/.local/share/applications).
int run_kde_install(std::ostream& out, std::ostream& err);

}  // namespace umf::provider
