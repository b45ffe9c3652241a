#include "provider/desktop/open_desktop.hpp"

#include <exception>

#include "provider/desktop/gnome/gnome_desktop.hpp"
#include "provider/desktop/kde/kde_desktop.hpp"
#include "provider/desktop/wlroots/layer_field_surface.hpp"
#include "provider/desktop/wlroots/wlroots_desktop.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"

namespace umf::provider {

namespace {

// What always works, whatever the desktop.
constexpr const char* kWhatWorks =
    "boards (--board), shared items (umf-provider share) and puts work as everywhere";

std::string no_backend_note() {
    return "This Wayland compositor has no umf backend, so no field is shown: an X11 overlay through Xwayland "
           "would hide the desktop and swallow its clicks. The window under the point and snapshots are off; " +
           std::string(kWhatWorks) +
           ". Sway, Hyprland, river, KDE Plasma and GNOME have backends; in an X11 session the overlay runs as "
           "usual.";
}

}  // namespace

OpenedDesktop open_desktop(const DesktopChoice& choice) {
    OpenedDesktop out;
    out.choice = choice;
    try {
        switch (choice.kind) {
        case DesktopKind::headless:
            return out;
        case DesktopKind::x11:
            out.desktop = std::make_shared<X11Desktop>();
            break;
        case DesktopKind::wlroots:
            out.desktop = make_wlroots_desktop();
            break;
        case DesktopKind::gnome:
            out.desktop = make_gnome_desktop();
            break;
        case DesktopKind::kde: {
            // KWin offers the same layer shell as the wlroots compositors.
            KdeDesktopOptions options;
            options.layer_surface = [](const std::string& display, QScreen* screen, ScreenField field,
                                       const std::vector<std::string>& palette) -> std::unique_ptr<FieldSurface> {
                return LayerFieldSurface::create(display, screen, std::move(field), palette);
            };
            out.desktop = make_kde_desktop(std::move(options));
            break;
        }
        case DesktopKind::unsupported_wayland:
            out.abilities.notes.push_back(no_backend_note());
            return out;
        }
    } catch (const std::exception& e) {
        out.desktop.reset();
        out.abilities = {};
        out.abilities.notes.push_back("The " + to_string(choice.kind) + " desktop cannot be reached (" + e.what() +
                                      "): no field, no window under the point, no snapshots; " + kWhatWorks + ".");
        return out;
    }
    out.abilities = out.desktop->abilities();
    return out;
}

std::vector<std::string> describe_desktop(const OpenedDesktop& opened) {
    std::vector<std::string> lines;
    if (opened.choice.kind == DesktopKind::headless) return lines;
    std::string works;
    const DesktopAbilities& a = opened.abilities;
    for (const auto& [on, what] : {std::pair{a.field, "field"}, std::pair{a.windows, "windows"},
                                   std::pair{a.snapshots, "snapshots"}, std::pair{a.placement, "placement"}})
        if (on) works += (works.empty() ? "" : ", ") + std::string(what);
    lines.push_back("desktop: " + (opened.desktop ? opened.desktop->name() : to_string(opened.choice.kind)) + " (" +
                    opened.choice.reason + "): " + (works.empty() ? std::string("no desktop features") : works));
    for (const auto& note : a.notes) lines.push_back("desktop: " + note);
    return lines;
}

std::string desktop_summary(const OpenedDesktop& opened) {
    if (opened.abilities.field) return "The field is shown on " + (opened.desktop ? opened.desktop->name() : "this desktop") + ".";
    return "No field on this desktop (" + to_string(opened.choice.kind) + "): " + kWhatWorks + ".";
}

}  // namespace umf::provider
