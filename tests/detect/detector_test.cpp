#include "shared/detect/detector.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using test::Photo;

struct DetectorCase {
    const char* name;
    double pitch, yaw, roll, distance;
};

class DetectorOnBlankScreens : public ::testing::TestWithParam<DetectorCase> {};

TEST_P(DetectorOnBlankScreens, FindsTheAimPoint) {
    const DetectorCase c = GetParam();
    Field f = test::shipped_field("b4-64x36.json");
    Detector detector(f);
    Photo p = test::photograph_field(f, 0.5, c.pitch, c.yaw, c.roll, c.distance);
    Detection d = detector.detect(p.view());
    ASSERT_TRUE(d.found) << c.name << ": " << d.failure;
    const cv::Point2d truth = sim::image_to_field(p.shot, p.placement, {p.view().width / 2.0, p.view().height / 2.0});
    const double error = std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y);
    EXPECT_LT(error, 0.02) << c.name << ": found (" << d.aim_field.x() << ", " << d.aim_field.y() << "), truth ("
                           << truth.x << ", " << truth.y << ")";
    EXPECT_GE(d.windows, 10);
    EXPECT_GT(d.confidence, 0.95);
    EXPECT_GT(d.pixels_visited, 0);
    EXPECT_LT(d.pixels_visited, 640 * 480 / 3);  // sparse: scanlines and edge profiles
    // Another aim point: a corner of the image.
    Detection corner = detector.detect(p.view(), Eigen::Vector2d(100, 80));
    ASSERT_TRUE(corner.found);
    const cv::Point2d truth2 = sim::image_to_field(p.shot, p.placement, {100, 80});
    EXPECT_LT(std::hypot(corner.aim_field.x() - truth2.x, corner.aim_field.y() - truth2.y), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Poses, DetectorOnBlankScreens,
                         ::testing::Values(DetectorCase{"straight", 0, 0, 0, 300}, DetectorCase{"rolled", 0, 0, 33, 300},
                                           DetectorCase{"upside_down", 0, 0, 190, 300},
                                           DetectorCase{"tilted", 40, -25, 20, 250}, DetectorCase{"near", 10, 10, 100, 180}),
                         [](const ::testing::TestParamInfo<DetectorCase>& info) { return std::string(info.param.name); });

TEST(Detector, NeverPlacesAScreenWithoutTheField) {
    Field f = test::shipped_field("b4-64x36.json");
    Detector detector(f);
    for (auto kind : sim::kAllScreenKinds) {
        Photo p = test::photograph_field(f, 0, 10, 5, 20, 300, kind);
        EXPECT_FALSE(detector.detect(p.view()).found);
    }
    // Another field on the screen.
    Field other = test::shipped_field("b4-96x54.json");
    Photo p = test::photograph_field(other, 0.5, 0, 0, 15, 300);
    Detection d = detector.detect(p.view());
    EXPECT_FALSE(d.found) << "windows " << d.windows;
}

// Every candidate place that reaches the final check is counted, and each
// after the first must bring more evidence: a clear view is placed at the
// first; a screen without the field checks few and places none.
TEST(Detector, CountsTheCandidatePlacesItChecks) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    const Photo seen = test::photograph_field(f, 0.5, 0, 0, 0, 300);
    const Detection found = detector.detect(seen.view());
    ASSERT_TRUE(found.found);
    EXPECT_EQ(found.places_checked, 1);
    const Photo none = test::photograph_field(f, 0, 0, 0, 0, 300, sim::ScreenKind::document);
    const Detection missing = detector.detect(none.view());
    EXPECT_FALSE(missing.found);
    EXPECT_LE(missing.places_checked, 2);
}

TEST(Detector, BadImagesAreNotFoundNeverACrash) {
    Detector detector(test::shipped_field("b4-64x36.json"));
    std::vector<std::uint8_t> px(64, 128);
    EXPECT_FALSE(detector.detect(GreyView{nullptr, 10, 10, 10}).found);
    EXPECT_FALSE(detector.detect(GreyView{px.data(), 1, 1, 1}).found);
    EXPECT_FALSE(detector.detect(GreyView{px.data(), 8, 8, 4}).found);  // stride below width
    EXPECT_FALSE(detector.detect(GreyView{px.data(), 0, 8, 8}).found);
    Detection huge = detector.detect(GreyView{px.data(), 100000, 1, 100000});
    EXPECT_FALSE(huge.found);
    EXPECT_NE(huge.failure.find("invalid image"), std::string::npos);
}

}  // namespace

namespace {

// Text, code, pictures under the field: found from most poses, and when found, right.
TEST(Detector, FindsTheFieldOverBusyScreens) {
    Field f = test::shipped_field("b4-64x36.json");
    Detector detector(f);
    const double poses[][4] = {{0, 0, 0, 300}, {20, 15, 70, 300}, {-30, 10, 140, 280}, {40, -25, 20, 250},
                               {10, 10, 100, 180}};
    for (auto kind : {sim::ScreenKind::document, sim::ScreenKind::code_dark, sim::ScreenKind::web_page,
                      sim::ScreenKind::photo}) {
        int found = 0;
        for (const auto& pose : poses) {
            test::Photo p = test::photograph_field(f, 0.5, pose[0], pose[1], pose[2], pose[3], kind);
            Detection d = detector.detect(p.view());
            if (!d.found) continue;
            ++found;
            const cv::Point2d truth = sim::image_to_field(p.shot, p.placement, {320, 240});
            EXPECT_LT(std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y), 0.1)
                << "screen " << static_cast<int>(kind) << " pose " << pose[2];
        }
        EXPECT_GE(found, 4) << "screen " << static_cast<int>(kind);
    }
}

}  // namespace
