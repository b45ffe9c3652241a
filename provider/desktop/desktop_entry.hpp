// The provider's one desktop entry (umf-provider.desktop.in beside this
// file): the menu entry the packages install, the autostart entry "Start at
// login" writes and the entry `kde install` writes, which KWin reads to let
// the program take snapshots (kwin_screenshot.hpp). Only Exec differs.
#pragma once

#include <string>

namespace umf::provider {

// The file name every copy has: KWin and the autostart both look for it.
inline constexpr const char* kDesktopEntryName = "umf-provider.desktop";

// The entry with Exec naming `executable`: KWin matches a program by the
// absolute path of its executable, so callers pass one.
std::string provider_desktop_entry(const std::string& executable);

}  // namespace umf::provider
