// The module centring (module_centring.hpp): from a homography up to about
// half a module off around a point, the shift that puts the module centres
// on the modules, within a tenth of a module; nothing where the point's
// modules are not in the image.
#include "shared/detect/module_centring.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "shared/detect/module_edges.hpp"
#include "tests/detect/rendered_field.hpp"
#include "tests/support/shipped_field.hpp"

using namespace umf;
using umf::test::aim_error;
using umf::test::render_field;
using umf::test::seen_at_an_angle;

namespace {

Eigen::Matrix3d shift_by(const Eigen::Vector2d& by) {
    Eigen::Matrix3d t = Eigen::Matrix3d::Identity();
    t.topRightCorner<2, 1>() = by;
    return t;
}

struct CentringCase {
    double module_px;
    cv::Size size;
    double blur_px;
};

TEST(ModuleCentring, PutsTheCentresOnTheModulesFromUpToHalfAModuleOff) {
    const Field f = test::shipped_field("b4-64x36.json");
    const std::vector<double> brightness = module_brightness(f);
    for (const CentringCase c : {CentringCase{7, {640, 480}, 0.8}, CentringCase{12, {640, 480}, 1.0},
                                 CentringCase{26, {1280, 720}, 1.5}}) {
        const Eigen::Matrix3d truth = seen_at_an_angle(c.module_px, c.size);
        const cv::Mat image = render_field(f, truth, c.size, c.blur_px);
        const GreyView view{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
        const Eigen::Vector2d centre(c.size.width / 2.0, c.size.height / 2.0);
        for (const Eigen::Vector2d& off : {Eigen::Vector2d(0.45, 0), Eigen::Vector2d(0, -0.45),
                                           Eigen::Vector2d(0.3, 0.35), Eigen::Vector2d(-0.4, -0.2),
                                           Eigen::Vector2d(0, 0)}) {
            SCOPED_TRACE("module px " + std::to_string(c.module_px) + ", off " + std::to_string(off.x()) + " " +
                         std::to_string(off.y()));
            // Every module centre of `start` lies `off` from the true one.
            const Eigen::Matrix3d start = truth * shift_by(-off);
            ASSERT_NEAR(aim_error(truth, start, c.size), off.norm(), 1e-6);
            const Eigen::Vector2d at = *apply_homography(start.inverse(), centre);
            const Eigen::Vector2d shift = centring_shift(view, f, brightness, start, at);
            EXPECT_LT((shift - off).norm(), 0.1);
            EXPECT_LT(aim_error(truth, start * shift_by(shift), c.size), 0.1);
        }
    }
}

TEST(ModuleCentring, LeavesThePlaceWhereItsModulesAreNotInTheImage) {
    const Field f = test::shipped_field("b4-64x36.json");
    const std::vector<double> brightness = module_brightness(f);
    const cv::Size size(640, 480);
    const Eigen::Matrix3d truth = seen_at_an_angle(12, size);
    const cv::Mat image = render_field(f, truth, size, 1.0);
    const GreyView view{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
    const Eigen::Matrix3d start = truth * shift_by(Eigen::Vector2d(-0.4, 0));
    // Off the field, no point at all, and one past a million modules.
    for (const Eigen::Vector2d& at :
         {Eigen::Vector2d(-30, -30), Eigen::Vector2d(std::nan(""), 3), Eigen::Vector2d(1e12, 0)})
        EXPECT_EQ(centring_shift(view, f, brightness, start, at), Eigen::Vector2d::Zero()) << at.transpose();
    // A place whose modules around the point all lie beyond the image's edge.
    Eigen::Matrix3d beyond = Eigen::Matrix3d::Identity();
    beyond(0, 2) = 2000;
    EXPECT_EQ(centring_shift(view, f, brightness, beyond * start, Eigen::Vector2d(24, 14)), Eigen::Vector2d::Zero());
}

}  // namespace
