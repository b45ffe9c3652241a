// One field over several screens: each screen shows its own part, the parts
// do not overlap, and a field point maps back to the right screen's pixels.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include "provider/screen/desktop_layout.hpp"
#include "provider/service/service.hpp"

namespace {

using namespace umf::provider;
namespace p = umf::protocol;

TEST(DesktopLayout, OneScreenIsTheScreensOwnField) {
    const auto layout = lay_out_desktop({{"DP-1", 0, 0, 1920, 1080}});
    const ScreenField alone = screen_field_for(1920, 1080);
    ASSERT_EQ(layout.screens.size(), 1u);
    EXPECT_EQ(layout.field.id, alone.field.id);
    EXPECT_EQ(layout.screens[0].field.placement, alone.placement);
    EXPECT_DOUBLE_EQ(layout.screens[0].region.u1, 64.0);
}

TEST(DesktopLayout, TwoScreensShareOneFieldWithoutOverlap) {
    // A laptop below-left of a 4K-wide pair's... plainly: two 1920 x 1080 side by side, a third below.
    const auto layout = lay_out_desktop({{"left", 0, 0, 1920, 1080}, {"right", 1920, 0, 1920, 1080},
                                         {"below", 0, 1080, 1366, 768}});
    ASSERT_EQ(layout.screens.size(), 3u);
    EXPECT_GE(layout.field.width * layout.screens[0].field.placement.module_px, 3840.0);
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < i; ++j) {
            const auto& a = layout.screens[i].region;
            const auto& b = layout.screens[j].region;
            EXPECT_FALSE(a.u0 < b.u1 && b.u0 < a.u1 && a.v0 < b.v1 && b.v0 < a.v1) << i << " and " << j;
        }
    // Through the service: a point on the right screen lands on its pixels and the desktop's.
    Service service(service_config_for(layout), "layout-test-token-0123456789");
    const auto& right = layout.screens[1];
    const double u = (right.region.u0 + right.region.u1) / 2, v = (right.region.v0 + right.region.v1) / 2;
    const auto point = service.screen_point({u, v});
    ASSERT_TRUE(point);
    EXPECT_EQ(point->screen, 1);
    const auto expected = umf::overlay::field_to_screen(right.field.placement, u, v);
    EXPECT_DOUBLE_EQ(point->x, expected.x);
    EXPECT_DOUBLE_EQ(point->root_x, expected.x + 1920);
    EXPECT_GE(point->x, 0);
    EXPECT_LT(point->x, 1920);
    // The welcome's screens carry the regions; it encodes and parses back.
    const auto& screens = service.screens()->field.screens;
    ASSERT_EQ(screens.size(), 3u);
    EXPECT_EQ(screens[2].name, "below");
    const p::Welcome w{std::nullopt, service.config().provider, service.screens()->field, service.config().overlay,
                       service.config().limits};
    EXPECT_TRUE(std::holds_alternative<p::Message>(p::parse_message(p::encode(w), p::kRequesterLimits)));
}

// Regions of a layout's screens pairwise apart.
void expect_disjoint(const DesktopLayout& layout) {
    for (std::size_t i = 0; i < layout.screens.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) {
            const auto& a = layout.screens[i].region;
            const auto& b = layout.screens[j].region;
            EXPECT_FALSE(a.u0 < b.u1 && b.u0 < a.u1 && a.v0 < b.v1 && b.v0 < a.v1) << i << " and " << j;
        }
}

TEST(DesktopLayout, KeepsTheWantedModuleSize) {
    // The kiosk's 40 px on one screen: the 64 x 36 field reaches past the edges.
    const auto big = lay_out_desktop({{"DP-1", 0, 0, 1920, 1080, 40.0}});
    EXPECT_DOUBLE_EQ(big.screens[0].field.placement.module_px, 40.0);
    EXPECT_EQ(big.field.width, 64);
    EXPECT_LT(big.screens[0].field.placement.origin_x, 0.0);
    EXPECT_DOUBLE_EQ(big.screens[0].region.u1 - big.screens[0].region.u0, 1920.0 / 40.0);
    // Two screens at 36 px: the largest field covers both at that size.
    const auto pair = lay_out_desktop({{"left", 0, 0, 1920, 1080, 36.0}, {"right", 1920, 0, 1920, 1080, 36.0}});
    EXPECT_DOUBLE_EQ(pair.screens[1].field.placement.module_px, 36.0);
    EXPECT_GE(pair.field.width * 36, 3840);
    expect_disjoint(pair);
    // At 24 px no shipped field is wide enough (160 modules): the modules grow
    // to what covers.
    const auto grown = lay_out_desktop({{"left", 0, 0, 1920, 1080, 24.0}, {"right", 1920, 0, 1920, 1080, 24.0}});
    EXPECT_DOUBLE_EQ(grown.screens[0].field.placement.module_px, 32.0);
    expect_disjoint(grown);
}

TEST(DesktopLayout, ScreensOfDifferentDensityEachKeepTheirModuleSize) {
    // A 1080p screen at 30 px beside a 4K laptop panel at 60 px (both 96 dpi
    // presets scaled to their density), the laptop to the left and lower.
    const std::vector<DesktopScreen> desktop{{"HDMI-1", 3840, 0, 1920, 1080, 30.0},
                                             {"eDP-1", 0, 200, 3840, 2160, 60.0}};
    const auto layout = lay_out_desktop(desktop);
    ASSERT_EQ(layout.screens.size(), 2u);
    const double m0 = layout.screens[0].field.placement.module_px, m1 = layout.screens[1].field.placement.module_px;
    // The same factor on both, grown only as far as the shipped fields need.
    EXPECT_NEAR(m1 / m0, 2.0, 0.05);
    EXPECT_GE(m0, 30.0);
    EXPECT_LE(m0, 40.0);
    expect_disjoint(layout);
    // Each screen is covered, and the desktop's left screen shows the left columns.
    for (const auto& s : layout.screens) {
        EXPECT_NEAR(s.region.u1 - s.region.u0, s.screen.width / s.field.placement.module_px, 1e-9);
        EXPECT_NEAR(s.region.v1 - s.region.v0, s.screen.height / s.field.placement.module_px, 1e-9);
    }
    EXPECT_LT(layout.screens[1].region.u0, layout.screens[0].region.u0);
    // A point resolves to the screen that shows it.
    Service service(service_config_for(layout), "layout-test-token-0123456789");
    for (int i = 0; i < 2; ++i) {
        const auto& r = layout.screens[i].region;
        const auto point = service.screen_point({(r.u0 + r.u1) / 2, (r.v0 + r.v1) / 2});
        ASSERT_TRUE(point);
        EXPECT_EQ(point->screen, i);
        EXPECT_NEAR(point->x, desktop[i].width / 2.0, 1.0);
        EXPECT_NEAR(point->y, desktop[i].height / 2.0, 1.0);
    }
}

TEST(DesktopLayout, ModuleSizeFollowsTheScreensDensity) {
    EXPECT_DOUBLE_EQ(module_px_for_density(30.0, 96.0), 30.0);
    EXPECT_DOUBLE_EQ(module_px_for_density(30.0, 192.0), 60.0);
    EXPECT_DOUBLE_EQ(module_px_for_density(30.0, 0.0), 30.0);     // no size reported
    EXPECT_DOUBLE_EQ(module_px_for_density(30.0, 5000.0), 30.0);  // an absurd one
}

TEST(DesktopLayout, RefusesWhatCannotBeLaidOut) {
    EXPECT_THROW(lay_out_desktop({}), std::invalid_argument);
    EXPECT_THROW(lay_out_desktop({{"a", 0, 0, 0, 1080}}), std::invalid_argument);
    EXPECT_THROW(lay_out_desktop({{"a", 0, 0, 1920, 1080}, {"mirror", 0, 0, 1920, 1080}}), std::invalid_argument);
}

}  // namespace

#endif
