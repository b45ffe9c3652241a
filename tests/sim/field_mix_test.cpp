// Tests of mixing the field into screen content.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <string>

#include "shared/field/field_io.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"

namespace {

using namespace umf::sim;

umf::Field k3_field() { return umf::load_field(std::string(UMF_DATA_DIR) + "/fields/k3e4-64x36.json"); }

TEST(SimFieldMix, ModuleCentresAreTheBlend) {
    const umf::Field field = k3_field();
    const cv::Mat screen = make_screen(ScreenKind::photo, {700, 420}, 2);
    const FieldPlacement placement{{13.3, 21.7}, 9.37};  // fractional on purpose
    const double opacity = 0.3;
    const cv::Mat mixed = mix_field(screen, field, placement, opacity);
    const std::vector<cv::Vec3b> palette = palette_bgr(field);
    int checked = 0;
    for (int i = 0; i < field.height; ++i)
        for (int j = 0; j < field.width; ++j) {
            const cv::Point2d centre = field_to_screen(placement, {j + 0.5, i + 0.5});
            const int x = static_cast<int>(std::floor(centre.x));
            const int y = static_cast<int>(std::floor(centre.y));
            if (x >= screen.cols || y >= screen.rows) continue;
            const cv::Vec3b content = screen.at<cv::Vec3b>(y, x);
            const cv::Vec3b colour = palette[field.at(i, j)];
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(mixed.at<cv::Vec3b>(y, x)[c], (1 - opacity) * content[c] + opacity * colour[c], 1.0)
                    << "module " << i << "," << j;
            ++checked;
        }
    EXPECT_EQ(checked, field.width * field.height);
}

TEST(SimFieldMix, PixelsOffTheFieldAreUnchanged) {
    const umf::Field field = k3_field();
    const cv::Mat screen = make_screen(ScreenKind::document, {640, 360}, 4);
    // Reaches past the right and bottom edges of the screen.
    const FieldPlacement placement{{100.6, 80.2}, 8.8};
    const cv::Mat mixed = mix_field(screen, field, placement, 1.0);
    int changed_off = 0;
    int on = 0;
    for (int y = 0; y < screen.rows; ++y)
        for (int x = 0; x < screen.cols; ++x) {
            const cv::Point2d uv = screen_to_field(placement, {x + 0.5, y + 0.5});
            const bool on_field = uv.x >= 0 && uv.y >= 0 && uv.x < field.width && uv.y < field.height;
            if (on_field)
                ++on;
            else if (mixed.at<cv::Vec3b>(y, x) != screen.at<cv::Vec3b>(y, x))
                ++changed_off;
        }
    EXPECT_EQ(changed_off, 0);
    EXPECT_GT(on, 50000);
}

TEST(SimFieldMix, FieldAndScreenCoordinatesInvert) {
    const FieldPlacement placement{{-40.5, 12.25}, 17.3};
    const cv::Point2d uv(12.345, 30.5);
    const cv::Point2d back = screen_to_field(placement, field_to_screen(placement, uv));
    EXPECT_NEAR(back.x, uv.x, 1e-12);
    EXPECT_NEAR(back.y, uv.y, 1e-12);
    EXPECT_EQ(field_to_screen(placement, {0, 0}), placement.origin);
}

TEST(SimFieldMix, PaletteIsBgr) {
    umf::Field field = umf::make_field(4, 4, 3, 2, umf::WindowKey::modules);
    field.palette = {"#ff8000", "#0000ff"};
    const auto palette = palette_bgr(field);
    EXPECT_EQ(palette[0], cv::Vec3b(0, 128, 255));
    EXPECT_EQ(palette[1], cv::Vec3b(255, 0, 0));
    field.palette.clear();
    EXPECT_EQ(palette_bgr(field)[1], cv::Vec3b(255, 255, 255));
}

}  // namespace
