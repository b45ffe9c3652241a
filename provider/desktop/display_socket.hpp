// Whether the display a session names is there: its Wayland compositor and
// its X server answer on their sockets. The provider's keeper asks this
// after the desktop went away, to know when to bring the field back.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "provider/desktop/desktop_choice.hpp"

namespace umf::provider {

struct DisplaySocket {
    std::string what;  // "Wayland display wayland-1", "X display :0"
    std::filesystem::path path;
    bool abstract = false;  // Linux's abstract namespace (X servers listen on both)
};

// The sockets to try, one or more per named display: WAYLAND_DISPLAY is a
// name in the runtime directory or an absolute path; DISPLAY ":N", ":N.S"
// or "unix:N" is /tmp/.X11-unix/XN. A display on another host gives
// nothing to try. Pure.
std::vector<DisplaySocket> display_sockets(const DesktopFacts& facts, const std::string& runtime_dir);

// True when every display the session names has a socket that accepts a
// connection (for X: the file or the abstract name); connects and closes.
bool displays_answer(const DesktopFacts& facts, const std::string& runtime_dir);

}  // namespace umf::provider
