// Which desktop backend a session gets (provider/desktop/desktop_choice.hpp).
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>

#include <stdexcept>

#include "provider/desktop/desktop_choice.hpp"

namespace umf::provider {
namespace {

DesktopFacts wayland(const std::string& desktop) {
    DesktopFacts facts;
    facts.session_type = "wayland";
    facts.wayland_display = "wayland-1";
    facts.x_display = ":0";  // Xwayland runs beside most compositors
    facts.current_desktop = desktop;
    return facts;
}

TEST(DesktopSession, WaylandDesktopsByName) {
    EXPECT_EQ(choose_desktop(wayland("GNOME")).kind, DesktopKind::gnome);
    EXPECT_EQ(choose_desktop(wayland("ubuntu:GNOME")).kind, DesktopKind::gnome);
    EXPECT_EQ(choose_desktop(wayland("KDE")).kind, DesktopKind::kde);
    EXPECT_EQ(choose_desktop(wayland("sway")).kind, DesktopKind::wlroots);
    EXPECT_EQ(choose_desktop(wayland("Hyprland")).kind, DesktopKind::wlroots);
    EXPECT_EQ(choose_desktop(wayland("river")).kind, DesktopKind::wlroots);
    // A word inside another entry is not a match.
    EXPECT_EQ(choose_desktop(wayland("gnomeish")).kind, DesktopKind::unsupported_wayland);
}

TEST(DesktopSession, CompositorSocketsNameWlroots) {
    DesktopFacts facts = wayland("");
    facts.swaysock = "/run/user/1000/sway-ipc.sock";
    EXPECT_EQ(choose_desktop(facts).kind, DesktopKind::wlroots);
    facts = wayland("");
    facts.hyprland = "abc";
    EXPECT_EQ(choose_desktop(facts).kind, DesktopKind::wlroots);
}

TEST(DesktopSession, AnUnknownCompositorIsNeverTreatedAsX11) {
    // weston with Xwayland: DISPLAY is set, but X11 windows there cannot
    // be click-through over native ones.
    const DesktopChoice choice = choose_desktop(wayland("weston"));
    EXPECT_EQ(choice.kind, DesktopKind::unsupported_wayland);
    EXPECT_TRUE(is_wayland(choice.kind));
    EXPECT_NE(choice.reason.find("XDG_CURRENT_DESKTOP=weston"), std::string::npos) << choice.reason;
    const DesktopFacts only_type{.session_type = "wayland", .wayland_display = "", .x_display = ":1",
                                 .current_desktop = "", .swaysock = "", .hyprland = ""};
    EXPECT_EQ(choose_desktop(only_type).kind, DesktopKind::unsupported_wayland);
}

TEST(DesktopSession, X11AndHeadless) {
    // GNOME on Xorg is an X11 desktop.
    const DesktopFacts x11{.session_type = "x11", .wayland_display = "", .x_display = ":0",
                           .current_desktop = "GNOME", .swaysock = "", .hyprland = ""};
    EXPECT_EQ(choose_desktop(x11).kind, DesktopKind::x11);
    EXPECT_FALSE(is_wayland(DesktopKind::x11));
    EXPECT_EQ(choose_desktop(DesktopFacts{}).kind, DesktopKind::headless);
}

TEST(DesktopSession, TheOptionWins) {
    EXPECT_EQ(choose_desktop(wayland("GNOME"), "x11").kind, DesktopKind::x11);
    EXPECT_EQ(choose_desktop(DesktopFacts{}, "wlroots").kind, DesktopKind::wlroots);
    EXPECT_EQ(choose_desktop(wayland("sway"), "KDE").kind, DesktopKind::kde);
    EXPECT_EQ(choose_desktop(wayland("sway"), "gnome").kind, DesktopKind::gnome);
    EXPECT_EQ(choose_desktop(wayland("sway"), "none").kind, DesktopKind::headless);
    EXPECT_THROW(choose_desktop(wayland("sway"), "windows"), std::invalid_argument);
}

}  // namespace
}  // namespace umf::provider

#endif  // UMF_PROVIDER_TESTS
