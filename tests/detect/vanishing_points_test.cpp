#include "shared/detect/vanishing_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using Case = test::PhotoCase;

class VanishingPointsOnPhotos : public ::testing::TestWithParam<Case> {};

// Largest angle, over a few image points, between the direction towards the
// found vanishing point and towards the true one.
double worst_angle_deg(const Eigen::Vector3d& found, const Eigen::Vector3d& truth, int w, int h) {
    double worst = 0;
    for (Eigen::Vector2d p : {Eigen::Vector2d(w / 2.0, h / 2.0), Eigen::Vector2d(w * 0.2, h * 0.2),
                              Eigen::Vector2d(w * 0.8, h * 0.7)}) {
        const double c = std::abs(direction_to(found, p).dot(direction_to(truth, p)));
        worst = std::max(worst, std::acos(std::min(1.0, c)) * 180 / M_PI);
    }
    return worst;
}

TEST_P(VanishingPointsOnPhotos, MatchTheGridsDirections) {
    const Case c = GetParam();
    Field f = test::shipped_field("b4-64x36.json");
    test::Photo photo = test::photograph_field(f, c.opacity, c.pitch, c.yaw, c.roll, c.distance, c.screen);
    GreyView view = photo.view();
    auto scan = find_edgels(view);
    auto vp = find_vanishing_points(scan.edgels, view.width, view.height);
    ASSERT_TRUE(vp.found) << c.name;

    // The screen's axes, seen by the camera, are the columns of the screen-to-image homography.
    const cv::Matx33d h = sim::screen_to_image(photo.geometry, photo.camera, photo.pose);
    const Eigen::Vector3d along_u(h(0, 0), h(1, 0), h(2, 0)), along_v(h(0, 1), h(1, 1), h(2, 1));
    const auto& a = vp.family[0].vanishing_point;
    const auto& b = vp.family[1].vanishing_point;
    const double straight = std::max(worst_angle_deg(a, along_u, view.width, view.height),
                                     worst_angle_deg(b, along_v, view.width, view.height));
    const double crossed = std::max(worst_angle_deg(a, along_v, view.width, view.height),
                                    worst_angle_deg(b, along_u, view.width, view.height));
    // Sobel directions on a few hundred edgels pin the directions to about
    // two degrees; the grid-line stage refines them from edgel positions.
    EXPECT_LT(std::min(straight, crossed), 2.5) << c.name;
    EXPECT_GT(vp.family[0].edgels.size(), 30u);
    EXPECT_GT(vp.family[1].edgels.size(), 30u);
}

INSTANTIATE_TEST_SUITE_P(
    Poses, VanishingPointsOnPhotos,
    ::testing::Values(Case{"straight", sim::ScreenKind::blank, 0.5, 0, 0, 0, 300},
                      Case{"rolled", sim::ScreenKind::blank, 0.5, 0, 0, 33, 300},
                      Case{"tilted", sim::ScreenKind::blank, 0.5, 40, -25, 20, 250},
                      Case{"document", sim::ScreenKind::document, 0.4, 20, 15, 70, 300},
                      Case{"web_page", sim::ScreenKind::web_page, 0.4, -30, 10, 140, 280}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

// Compressed frames: the flat areas the noise is estimated from are flat,
// so the estimate is 0, while the gradients on the edges scatter by several
// degrees (ringing, the corners of small modules). The families must still
// take in the scattered edgels, and leave the content's out.
TEST(VanishingPoints, TakeInEdgelsScatteredBeyondWhatTheNoiseEstimateSays) {
    std::mt19937 rng(5);
    std::normal_distribution<double> tilt(0.0, 5.0 * M_PI / 180);
    std::uniform_real_distribution<double> pos(20, 620), any(0, M_PI);
    std::vector<Edgel> edgels;
    for (int i = 0; i < 600; ++i) {
        // Grid edgels: a grid turned 20 degrees seen straight on, gradients
        // along the grid's axes give or take the scatter.
        const double axis = (i % 2 ? 20.0 : 110.0) * M_PI / 180 + tilt(rng);
        const double g = 100;
        edgels.push_back(Edgel{static_cast<float>(pos(rng)), static_cast<float>(pos(rng) * 0.75),
                               static_cast<float>(g * std::cos(axis)), static_cast<float>(g * std::sin(axis))});
    }
    for (int i = 0; i < 200; ++i) {  // content at any angle
        const double a = any(rng);
        edgels.push_back(Edgel{static_cast<float>(pos(rng)), static_cast<float>(pos(rng) * 0.75),
                               static_cast<float>(150 * std::cos(a)), static_cast<float>(150 * std::sin(a))});
    }
    const VanishingPoints vp = find_vanishing_points(edgels, 640, 480, {}, 0.0);
    ASSERT_TRUE(vp.found);
    for (const LineFamily& family : vp.family) {
        int grid = 0;
        for (int i : family.edgels) grid += i < 600;
        // 300 grid edgels a family; at a 4 degree tolerance about 58 % would pass.
        EXPECT_GE(grid, 270);
        // Content within the family's tolerance: about 15 degrees either side of 180.
        EXPECT_LE(static_cast<int>(family.edgels.size()) - grid, 45);
    }
}

TEST(VanishingPoints, TooFewEdgelsAreNotFound) {
    std::vector<Edgel> few(5, Edgel{10, 10, 1, 0});
    EXPECT_FALSE(find_vanishing_points(few, 100, 100).found);
    EXPECT_FALSE(find_vanishing_points({}, 100, 100).found);
}

}  // namespace
