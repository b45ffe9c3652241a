// The desktop backend for a session, opened (desktop/desktop_choice.hpp chooses
// which), and what it tells the console: which backend runs and what does
// not work there. A session whose backend cannot be opened, or a Wayland
// compositor with none, gets no desktop: no field is shown there at all
// (an X11 window through Xwayland would hide the desktop and take its
// clicks), while boards, shared items and puts keep working.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"
#include "provider/desktop/desktop_choice.hpp"

namespace umf::provider {

struct OpenedDesktop {
    DesktopChoice choice;
    std::shared_ptr<Desktop> desktop;  // null: headless, or no backend here
    DesktopAbilities abilities;        // all false without a desktop, with notes saying why
};

OpenedDesktop open_desktop(const DesktopChoice& choice);

// The console's lines: "desktop: x11 (X11 session (DISPLAY=:0)): field,
// windows, snapshots, placement", then what does not work and why.
std::vector<std::string> describe_desktop(const OpenedDesktop& opened);

// One line for the tray's tooltip or menu: what works here.
std::string desktop_summary(const OpenedDesktop& opened);

}  // namespace umf::provider
