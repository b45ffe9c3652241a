// The refit (refine.hpp): from a homography a fraction of a module off, the
// field's own edges bring the aim to within a few hundredths of a module,
// whatever the modules' size in pixels; its profiles across the edges are
// sampled a tenth of a module apart on large modules, one pixel apart on
// small ones.
#include "shared/detect/refine.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "shared/detect/module_edges.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

// The field seen through `field_to_image`, each pixel the mean of 4 x 4
// samples, blurred as a camera's optics do, faint (24 grey levels between
// the darkest and brightest module) over mid-grey, with noise.
cv::Mat render(const Field& f, const Eigen::Matrix3d& field_to_image, cv::Size size, double blur_px) {
    const std::vector<double> b = module_brightness(f);
    const auto [lo, hi] = std::minmax_element(b.begin(), b.end());
    const Eigen::Matrix3d to_field = field_to_image.inverse();
    cv::Mat out(size, CV_8UC1);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            double sum = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const auto q = apply_homography(to_field, Point2(x + (sx + 0.5) / 4, y + (sy + 0.5) / 4));
                    double level = 0.5;
                    if (q && q->x() >= 0 && q->y() >= 0 && q->x() < f.width && q->y() < f.height)
                        level = (b[f.at(static_cast<int>(q->y()), static_cast<int>(q->x()))] - *lo) / (*hi - *lo);
                    sum += level;
                }
            out.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(116 + 24 * sum / 16);
        }
    cv::GaussianBlur(out, out, cv::Size(), blur_px);
    cv::Mat noise(size, CV_16SC1);
    cv::RNG rng(5);
    rng.fill(noise, cv::RNG::NORMAL, 0, 2);
    cv::Mat grey;
    out.convertTo(grey, CV_16SC1);
    grey += noise;
    grey.convertTo(out, CV_8UC1);
    return out;
}

// A field seen at an angle: `module_px` pixels a module at the field point
// (24, 14), which lands at the image's centre.
Eigen::Matrix3d seen_at_an_angle(double module_px, cv::Size size) {
    Eigen::Matrix3d h;
    h << module_px, 0.12 * module_px, 0, -0.08 * module_px, 0.95 * module_px, 0, 0.004, 0.002, 1;
    // Move the field point (24, 14) to the image centre.
    const Point2 at = *apply_homography(h, Point2(24, 14));
    Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
    shift(0, 2) = size.width / 2.0 - at.x();
    shift(1, 2) = size.height / 2.0 - at.y();
    return shift * h;
}

// How far (modules) the image centre lands from where it truly is.
double aim_error(const Eigen::Matrix3d& truth, const Eigen::Matrix3d& fitted, cv::Size size) {
    const Point2 centre(size.width / 2.0, size.height / 2.0);
    return (*apply_homography(fitted.inverse(), centre) - *apply_homography(truth.inverse(), centre)).norm();
}

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
        const cv::Mat image = render(f, truth, c.size, c.blur_px);
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
