#include "provider/desktop/desktop_choice.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace umf::provider {

namespace {

std::string env(const char* name) {
    const char* value = std::getenv(name);
    return value ? std::string(value) : std::string();
}

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

// XDG_CURRENT_DESKTOP is a colon-separated list, most specific first
// ("ubuntu:GNOME", "Budgie:GNOME"); any entry naming a known desktop counts.
bool names_desktop(const std::string& list, const std::vector<std::string>& names) {
    const std::string all = lower(list);
    std::size_t start = 0;
    while (start <= all.size()) {
        const std::size_t end = std::min(all.find(':', start), all.size());
        const std::string entry = all.substr(start, end - start);
        for (const auto& name : names)
            if (entry == name) return true;
        start = end + 1;
    }
    return false;
}

}  // namespace

DesktopFacts desktop_facts_from_environment() {
    return {env("XDG_SESSION_TYPE"), env("WAYLAND_DISPLAY"), env("DISPLAY"), env("XDG_CURRENT_DESKTOP"),
            env("SWAYSOCK"), env("HYPRLAND_INSTANCE_SIGNATURE")};
}

DesktopChoice choose_desktop(const DesktopFacts& facts, const std::optional<std::string>& override_name) {
    if (override_name) {
        const std::string name = lower(*override_name);
        if (name == "x11") return {DesktopKind::x11, "--desktop x11"};
        if (name == "wlroots" || name == "sway" || name == "hyprland") return {DesktopKind::wlroots, "--desktop " + name};
        if (name == "kde" || name == "plasma" || name == "kwin") return {DesktopKind::kde, "--desktop " + name};
        if (name == "gnome") return {DesktopKind::gnome, "--desktop gnome"};
        if (name == "none" || name == "headless") return {DesktopKind::headless, "--desktop " + name};
        throw std::invalid_argument("--desktop takes x11, wlroots, kde, gnome or none, not '" + *override_name + "'");
    }
    const bool wayland = !facts.wayland_display.empty() || lower(facts.session_type) == "wayland";
    if (wayland) {
        const std::string why = "Wayland session (" +
                                (facts.current_desktop.empty() ? std::string("XDG_CURRENT_DESKTOP unset")
                                                               : "XDG_CURRENT_DESKTOP=" + facts.current_desktop) +
                                ")";
        if (names_desktop(facts.current_desktop, {"gnome", "gnome-classic", "gnome-flashback"}))
            return {DesktopKind::gnome, why};
        if (names_desktop(facts.current_desktop, {"kde", "plasma"})) return {DesktopKind::kde, why};
        if (!facts.swaysock.empty() || !facts.hyprland.empty() ||
            names_desktop(facts.current_desktop, {"sway", "hyprland", "river", "wlroots", "labwc", "wayfire"}))
            return {DesktopKind::wlroots, why};
        return {DesktopKind::unsupported_wayland, why};
    }
    if (!facts.x_display.empty()) return {DesktopKind::x11, "X11 session (DISPLAY=" + facts.x_display + ")"};
    return {DesktopKind::headless, "no display (neither DISPLAY nor WAYLAND_DISPLAY is set)"};
}

std::string to_string(DesktopKind kind) {
    switch (kind) {
    case DesktopKind::headless: return "headless";
    case DesktopKind::x11: return "x11";
    case DesktopKind::wlroots: return "wlroots";
    case DesktopKind::kde: return "kde";
    case DesktopKind::gnome: return "gnome";
    case DesktopKind::unsupported_wayland: return "wayland (no backend)";
    }
    return "unknown";
}

bool is_wayland(DesktopKind kind) {
    return kind == DesktopKind::wlroots || kind == DesktopKind::kde || kind == DesktopKind::gnome ||
           kind == DesktopKind::unsupported_wayland;
}

}  // namespace umf::provider
