// One field over several screens: each screen shows its own part, the parts
// do not overlap, and a field point maps back to the right screen's pixels.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include "screen/desktop_layout.hpp"
#include "server/service.hpp"

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
    const auto& screens = service.config().field.screens;
    ASSERT_EQ(screens.size(), 3u);
    EXPECT_EQ(screens[2].name, "below");
    const p::Welcome w{std::nullopt, service.config().provider, service.config().field, service.config().overlay,
                       service.config().limits};
    EXPECT_TRUE(std::holds_alternative<p::Message>(p::parse_message(p::encode(w), p::kRequesterLimits)));
}

TEST(DesktopLayout, RefusesWhatCannotBeLaidOut) {
    EXPECT_THROW(lay_out_desktop({}), std::invalid_argument);
    EXPECT_THROW(lay_out_desktop({{"a", 0, 0, 0, 1080}}), std::invalid_argument);
    EXPECT_THROW(lay_out_desktop({{"a", 0, 0, 1920, 1080}, {"mirror", 0, 0, 1920, 1080}}), std::invalid_argument);
}

}  // namespace

#endif
