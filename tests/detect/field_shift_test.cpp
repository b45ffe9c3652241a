#include "shared/detect/field_shift.hpp"

#include <gtest/gtest.h>

#include <string>

#include "shared/detect/pulse_search.hpp"

#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

// The photo's true map from image pixels (centres at whole coordinates, as
// the detector counts them) to field modules.
Eigen::Matrix3d true_image_to_field(const test::Photo& p) {
    Eigen::Matrix3d to_screen, to_field, centres;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) to_screen(r, c) = p.shot.image_to_screen(r, c);
    const double m = p.placement.module_px;
    to_field << 1 / m, 0, -p.placement.origin.x / m, 0, 1 / m, -p.placement.origin.y / m, 0, 0, 1;
    centres << 1, 0, 0.5, 0, 1, 0.5, 0, 0, 1;
    return to_field * to_screen * centres;
}

// The map of a place that puts the field `off` pixels from where the frame shows it.
Eigen::Matrix3d shifted(const Eigen::Matrix3d& image_to_field, const Eigen::Vector2d& off) {
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    t.topRightCorner<2, 1>() = off;
    return image_to_field * t;
}

class FieldShiftOnBusyScreens : public ::testing::TestWithParam<sim::ScreenKind> {};

// A field at 3 % over the content, filmed at a slant: one frame's field is
// faint, but over the whole view its edges say where it is.
TEST_P(FieldShiftOnBusyScreens, FindsHowFarAPlaceIsOffInOneFaintFrame) {
    const Field f = test::shipped_field("b4-64x36.json");
    const test::Photo p = test::photograph_field(f, 0.03, 10, -15, 5, 450, GetParam());
    const Eigen::Matrix3d truth = true_image_to_field(p);
    const FieldShift right = field_shift(p.view(), f, truth);
    ASSERT_TRUE(right.measured) << right.edge_pixels << " edge pixels";
    EXPECT_GT(right.module_px, 6);
    EXPECT_LT(right.module_px, 16);
    EXPECT_LT(right.shift.norm(), 1.0) << right.shift.transpose();
    EXPECT_GT(right.place_t, 20);
    EXPECT_GT(right.place_t, 0.8 * right.best_t);
    for (const Eigen::Vector2d& off : {Eigen::Vector2d(4, -3), Eigen::Vector2d(-2, 5), Eigen::Vector2d(5, 0)}) {
        const FieldShift s = field_shift(p.view(), f, shifted(truth, off));
        ASSERT_TRUE(s.measured);
        EXPECT_LT((s.shift - off).norm(), 1.0) << "off " << off.transpose() << ", measured " << s.shift.transpose();
        EXPECT_LT(s.place_t, 0.5 * s.best_t) << "off " << off.transpose();
    }
}

INSTANTIATE_TEST_SUITE_P(Screens, FieldShiftOnBusyScreens,
                         ::testing::Values(sim::ScreenKind::document, sim::ScreenKind::spreadsheet,
                                           sim::ScreenKind::photo, sim::ScreenKind::blank),
                         [](const auto& info) { return std::string(sim::to_string(info.param)); });

// Without the field, the content alone: no shift stands out.
TEST(FieldShift, FindsNoStrongFieldWhereTheScreenShowsNone) {
    const Field f = test::shipped_field("b4-64x36.json");
    for (const sim::ScreenKind kind : {sim::ScreenKind::document, sim::ScreenKind::spreadsheet}) {
        const test::Photo p = test::photograph_field(f, 0, 10, -15, 5, 450, kind);
        const FieldShift s = field_shift(p.view(), f, shifted(true_image_to_field(p), {3, 2}));
        ASSERT_TRUE(s.measured);
        EXPECT_LT(s.best_t, 20) << sim::to_string(kind);
    }
}

TEST(FieldShift, MeasuresNothingOffTheField) {
    const Field f = test::shipped_field("b4-64x36.json");
    const test::Photo p = test::photograph_field(f, 0.03, 0, 0, 0, 450);
    // The map puts the whole frame far outside the field.
    Eigen::Matrix3d away = Eigen::Matrix3d::Identity();
    away.topRightCorner<2, 1>() = Eigen::Vector2d(1000, 1000);
    const FieldShift s = field_shift(p.view(), f, away * true_image_to_field(p));
    EXPECT_FALSE(s.measured);
    EXPECT_EQ(s.edge_pixels, 0);
}

// The pulse search's check (PulseSearchOptions::check_newest): a place
// that puts the field where the newest frame shows it holds; one that puts
// it 0.6 module off, where that frame's own field is plain, does not.
TEST(PulseSearch, RefusesAPlaceTheNewestFrameShowsTheFieldElsewhereFrom) {
    const Field f = test::shipped_field("b4-64x36.json");
    const test::Photo p = test::photograph_field(f, 0.04, 10, -15, 5, 450, sim::ScreenKind::spreadsheet);
    Detection right;
    right.found = true;
    right.image_to_field = true_image_to_field(p);
    const FieldShift measured = field_shift(p.view(), f, right.image_to_field);
    ASSERT_TRUE(measured.measured);
    Detection off = right;
    off.image_to_field = shifted(right.image_to_field, {0.6 * measured.module_px, 0});
    for (const bool check : {true, false}) {
        PulseSearchOptions options;
        options.check_newest = check;
        PulseSearch search(options);
        EXPECT_TRUE(search.holds_in_newest(off, f)) << "no frame kept: nothing to check against";
        search.add(p.view());
        EXPECT_TRUE(search.holds_in_newest(right, f));
        EXPECT_EQ(search.holds_in_newest(off, f), !check);
    }
}

}  // namespace
