// Tests of the camera simulator's geometry: the ground truth it reports must
// agree with the pixels it renders, and with the pinhole model.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "shared/field/field_io.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/homography.hpp"
#include "tests/sim/screen_content.hpp"

namespace {

using namespace umf::sim;

const ScreenGeometry kScreen{{1920, 1080}, 527};
const CameraModel kCamera{{1280, 720}, 65};

umf::Field shipped(const std::string& name) { return umf::load_field(std::string(UMF_DATA_DIR) + "/fields/" + name); }

double frac_distance_to_border(double t) { return std::min(t - std::floor(t), std::ceil(t) - t); }

int nearest_palette_index(const std::vector<cv::Vec3b>& palette, const cv::Vec3b& c) {
    int best = 0;
    double best_d = 1e9;
    for (std::size_t i = 0; i < palette.size(); ++i) {
        const double d = cv::norm(cv::Vec3d(palette[i]) - cv::Vec3d(c), cv::NORM_L1);
        if (d < best_d) best_d = d, best = static_cast<int>(i);
    }
    return best;
}

// Every image pixel on a grid that the ground truth puts well inside a module
// must show that module's colour. Returns how many pixels were checked.
int check_ground_truth(const Shot& shot, const umf::Field& field, const FieldPlacement& placement) {
    const std::vector<cv::Vec3b> palette = palette_bgr(field);
    int checked = 0;
    int wrong = 0;
    for (int y = 0; y < shot.bgr.rows; y += 5)
        for (int x = 0; x < shot.bgr.cols; x += 5) {
            const cv::Point2d uv = image_to_field(shot, placement, {x + 0.5, y + 0.5});
            if (uv.x < 0 || uv.y < 0 || uv.x >= field.width || uv.y >= field.height) continue;
            if (frac_distance_to_border(uv.x) < 0.15 || frac_distance_to_border(uv.y) < 0.15) continue;
            const int module = field.at(static_cast<int>(uv.y), static_cast<int>(uv.x));
            const cv::Vec3b seen = shot.bgr.at<cv::Vec3b>(y, x);
            ++checked;
            const double off = cv::norm(cv::Vec3d(seen) - cv::Vec3d(palette[module]), cv::NORM_INF);
            if (nearest_palette_index(palette, seen) != module || off > 12) {
                if (++wrong <= 5)
                    ADD_FAILURE() << "image (" << x << "," << y << ") field (" << uv.x << "," << uv.y << ") module "
                                  << module << " shows " << seen << " expected " << palette[module];
            }
        }
    EXPECT_EQ(wrong, 0) << "of " << checked;
    return checked;
}

TEST(SimCamera, GroundTruthMatchesPixelsStraightOn) {
    const umf::Field field = shipped("k3e4-64x36.json");
    const FieldPlacement placement = centred_placement(field, kScreen.pixels, 28.5);
    const cv::Mat screen = mix_field(make_screen(ScreenKind::document, kScreen.pixels, 3), field, placement, 1.0);
    const CameraPose pose{300, 0, 0, 0, {900.3, 560.7}};
    const Shot shot = photograph(screen, kScreen, kCamera, pose, {});
    EXPECT_GT(check_ground_truth(shot, field, placement), 15000);
}

TEST(SimCamera, GroundTruthMatchesPixelsTilted) {
    // The original authors' 5-grey field: five levels 64 apart test the
    // colour reproduction as well as the geometry.
    const umf::Field field = umf::load_field(std::string(UMF_TEST_DATA_DIR) + "/original-umf/sog5-19x31.json");
    const FieldPlacement placement{{500.25, 40.5}, 32.4};
    const cv::Mat screen = mix_field(make_screen(ScreenKind::photo, kScreen.pixels, 5), field, placement, 1.0);
    const CameraPose pose{350, 45, -30, 37, {800, 540}};
    const Shot shot = photograph(screen, kScreen, kCamera, pose, {});
    EXPECT_GT(check_ground_truth(shot, field, placement), 5000);
}

// Bilinear sample of a single-channel float image at a continuous point (the
// centre of pixel (x, y) being (x + 0.5, y + 0.5)).
double sample(const cv::Mat& img, cv::Point2d p) {
    const double x = p.x - 0.5;
    const double y = p.y - 0.5;
    const int x0 = static_cast<int>(std::floor(x));
    const int y0 = static_cast<int>(std::floor(y));
    const double fx = x - x0;
    const double fy = y - y0;
    const auto at = [&](int yy, int xx) { return static_cast<double>(img.at<float>(yy, xx)); };
    return (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x0 + 1)) + fy * ((1 - fx) * at(y0 + 1, x0) + fx * at(y0 + 1, x0 + 1));
}

// Where, in image pixels along a -> b, the step between two modules lies in
// the linear-light profile, minus where the ground truth puts it (the field
// point half way between a and b). The step is located by the area under the
// normalised profile, which any centred blur preserves, so unlike a
// half-way crossing it has no bias from where the edge falls in a pixel.
double edge_error(const cv::Mat& light, const Shot& shot, const FieldPlacement& placement, cv::Point2d a, cv::Point2d b) {
    const cv::Point2d p0 = field_to_image(shot, placement, a);
    const cv::Point2d p1 = field_to_image(shot, placement, b);
    const cv::Point2d edge = field_to_image(shot, placement, 0.5 * (a + b));
    const cv::Point2d dir = p1 - p0;
    const double length = cv::norm(dir);
    constexpr int n = 201;
    std::vector<double> profile(n);
    for (int i = 0; i < n; ++i) profile[i] = sample(light, p0 + dir * (i / (n - 1.0)));
    const double before = profile.front();
    const double after = profile.back();
    double area = 0;  // trapezoids
    for (int i = 1; i < n; ++i) area += 0.5 * ((profile[i - 1] - after) + (profile[i] - after)) / (before - after);
    const double step_at = area / (n - 1.0) * length;
    return step_at - (edge - p0).dot(dir) / length;
}

// Module edges must appear in the image exactly where the ground truth puts
// them, to a small fraction of a pixel: this pins down the half-pixel
// conventions of screen, placement and image.
void check_edges(const Shot& shot, const umf::Field& field, const FieldPlacement& placement) {
    cv::Mat grey;
    shot.grey.convertTo(grey, CV_32F, 1 / 255.0);
    cv::pow(grey, 2.2, grey);  // back to linear light, where blur keeps edges symmetric
    const cv::Rect inner(4, 4, shot.grey.cols - 8, shot.grey.rows - 8);
    double worst = 0;
    double total = 0;
    double signed_total = 0;
    int edges = 0;
    for (int i = 0; i < field.height; ++i)
        for (int j = 1; j < field.width; ++j) {
            // Vertical edge between (i, j - 1) and (i, j), crossed at mid height.
            if (field.at(i, j - 1) == field.at(i, j)) continue;
            const cv::Point2d a(j - 0.45, i + 0.5);
            const cv::Point2d b(j + 0.45, i + 0.5);
            if (!inner.contains(field_to_image(shot, placement, a)) || !inner.contains(field_to_image(shot, placement, b)))
                continue;
            const double error = edge_error(grey, shot, placement, a, b);
            worst = std::max(worst, std::abs(error));
            total += std::abs(error);
            signed_total += error;
            ++edges;
        }
    ASSERT_GT(edges, 100);
    EXPECT_LT(worst, 0.1) << "pixels";
    EXPECT_LT(total / edges, 0.03) << "pixels";
    EXPECT_LT(std::abs(signed_total / edges), 0.01) << "pixels: a shift of the whole image";
}

TEST(SimCamera, EdgesLandOnTheGroundTruth) {
    const umf::Field field = shipped("b4-64x36.json");
    // Whole pixels: mix_field colours each screen pixel by its centre, so
    // with fractional module sizes the screen itself puts edges up to half a
    // screen pixel off the continuous placement; here it must not.
    const FieldPlacement placement = centred_placement(field, kScreen.pixels, 27);
    ASSERT_EQ(placement.origin, cv::Point2d(96, 54));
    const cv::Mat screen = mix_field(make_screen(ScreenKind::blank, kScreen.pixels, 1), field, placement, 1.0);
    for (const CameraPose& pose : {CameraPose{300, 0, 0, 0, {955.3, 530.8}}, CameraPose{320, 35, 25, -20, {1000, 500}}}) {
        SCOPED_TRACE(pose.pitch_deg);
        check_edges(photograph(screen, kScreen, kCamera, pose, {}), field, placement);
    }
}

TEST(SimCamera, ImageCentreLooksAtTheAimPoint) {
    // Small images: only the geometry matters here.
    const ScreenGeometry screen{{480, 270}, 400};
    const CameraModel camera{{320, 180}, 70};
    const cv::Mat content = make_screen(ScreenKind::blank, screen.pixels, 1);
    for (const CameraPose& pose : {CameraPose{250, 0, 0, 0, {240, 135}}, CameraPose{400, 60, 0, 0, {100.5, 30.25}},
                                   CameraPose{180, -35, 50, 170, {470, 260}}, CameraPose{600, 10, -60, -95, {0, 0}}}) {
        const Shot shot = photograph(content, screen, camera, pose, {});
        EXPECT_NEAR(shot.centre_screen_px.x, pose.aim_screen_px.x, 1e-6);
        EXPECT_NEAR(shot.centre_screen_px.y, pose.aim_screen_px.y, 1e-6);
        EXPECT_TRUE(shot.centre_on_screen);
    }
    const Shot off = photograph(content, screen, camera, CameraPose{250, 0, 0, 0, {-20, 100}}, {});
    EXPECT_FALSE(off.centre_on_screen);
}

TEST(SimCamera, ModuleSizeFollowsThePinholeFormula) {
    const umf::Field field = shipped("b4-64x36.json");
    const FieldPlacement placement = centred_placement(field, kScreen.pixels, 30);
    const cv::Mat screen = mix_field(make_screen(ScreenKind::blank, kScreen.pixels, 1), field, placement, 1.0);
    const Shot shot = photograph(screen, kScreen, kCamera, CameraPose{300, 0, 0, 0, {960, 540}}, {}, 30);
    const double focal = 640 / std::tan(32.5 * CV_PI / 180);
    const double expected = 30 * (527.0 / 1920) * focal / 300;  // about 27.6 px
    EXPECT_NEAR(shot.module_px_in_image, expected, 1e-9 * expected);
    EXPECT_NEAR(shot.screen_px_in_image * 30, shot.module_px_in_image, 1e-12);
    // The same from the ground-truth mapping of the field itself.
    const cv::Point2d uv = image_to_field(shot, placement, {640, 360});
    const double step = cv::norm(field_to_image(shot, placement, uv + cv::Point2d(1, 0)) - cv::Point2d(640, 360));
    EXPECT_NEAR(step, expected, 1e-6);
}

TEST(SimCamera, PoseConventions) {
    const cv::Point2d aim(960, 540);
    const auto scale_at = [&](const CameraPose& pose, cv::Point2d p) {
        return screen_px_in_image_at(screen_to_image(kScreen, kCamera, pose), p);
    };
    // Pitch > 0: camera above, looking down, so the upper screen is nearer.
    EXPECT_GT(scale_at({300, 30, 0, 0, aim}, {960, 200}), scale_at({300, 30, 0, 0, aim}, {960, 900}));
    // Yaw > 0: camera on the right, so the right part is nearer.
    EXPECT_GT(scale_at({300, 0, 30, 0, aim}, {1700, 540}), scale_at({300, 0, 30, 0, aim}, {200, 540}));
    // Roll > 0: the screen's x axis appears turned counter-clockwise (upwards in image y-down coordinates).
    const cv::Matx33d h = screen_to_image(kScreen, kCamera, {300, 0, 0, 20, aim});
    const cv::Point2d x_axis = apply(h, aim + cv::Point2d(100, 0)) - apply(h, aim);
    EXPECT_GT(x_axis.x, 0);
    EXPECT_LT(x_axis.y, 0);
    EXPECT_NEAR(std::atan2(-x_axis.y, x_axis.x) * 180 / CV_PI, 20, 1e-9);
}

}  // namespace
