// The refit (refine.hpp): from a homography a fraction of a module off, the
// field's own edges bring the aim to within a few hundredths of a module,
// whatever the modules' size in pixels; its profiles across the edges are
// sampled a tenth of a module apart on large modules, one pixel apart on
// small ones.
#include "shared/detect/refine.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>

#include "shared/detect/module_edges.hpp"
#include "tests/detect/photo.hpp"
#include "tests/detect/rendered_field.hpp"

using namespace umf;
using umf::test::aim_error;
using umf::test::render_field;
using umf::test::seen_at_an_angle;

namespace {

struct RefitCase {
    double module_px;
    cv::Size size;
    double blur_px;
};

TEST(Refine, BringsTheAimToTheFieldsEdgesAtAnyModuleSize) {
    const Field f = test::shipped_field("b4-64x36.json");
    const ModuleEdges edges(f);
    for (const RefitCase c : {RefitCase{7, {640, 480}, 0.8}, RefitCase{12, {640, 480}, 1.0},
                              RefitCase{26, {1280, 720}, 1.5}, RefitCase{40, {1920, 1080}, 2.0}}) {
        SCOPED_TRACE("module px " + std::to_string(c.module_px));
        const Eigen::Matrix3d truth = seen_at_an_angle(c.module_px, c.size);
        const cv::Mat image = render_field(f, truth, c.size, c.blur_px);
        const GreyView view{image.data, image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step)};
        // A start a fifth of a module off and 2 % too large, as a vote leaves it.
        // (about the seed, where the windows voted).
        Eigen::Matrix3d off = Eigen::Matrix3d::Identity();
        off(0, 0) = off(1, 1) = 1.02;
        off(0, 2) = 0.15 - 0.02 * 24;
        off(1, 2) = -0.12 - 0.02 * 14;
        const Eigen::Matrix3d start = truth * off;
        ASSERT_GT(aim_error(truth, start, c.size), 0.15);

        long sampled = 0, every_pixel = 0;  // pixels read
        RefineOptions o;
        const Refinement r = refine_homography(view, f, edges, start, Point2(24, 14), o, sampled);
        o.sample_modules = 0;  // one pixel apart, whatever the module's size
        const Refinement dense = refine_homography(view, f, edges, start, Point2(24, 14), o, every_pixel);

        ASSERT_TRUE(r.refined);
        ASSERT_TRUE(dense.refined);
        EXPECT_LT(aim_error(truth, r.field_to_image, c.size), 0.03);
        EXPECT_LT(aim_error(truth, dense.field_to_image, c.size), 0.03);
        EXPECT_GT(r.edges_fitted, 0.8 * dense.edges_fitted);
        // Both fits place the aim alike: the samples' spacing costs no precision.
        EXPECT_LT(aim_error(dense.field_to_image, r.field_to_image, c.size), 0.02);
        EXPECT_GT(sampled, 0);
    }
}

}  // namespace
