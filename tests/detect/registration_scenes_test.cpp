// Frame registration and the pulse search on the pulsing benchmark's own
// frames (the tuning set's swing, tests/bench/scenario.hpp), where a
// failure was seen.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "shared/detect/frame_registration.hpp"
#include "shared/detect/pulse_search.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/screen_content.hpp"

namespace registration_scenes {

using namespace umf;

GreyView view(const cv::Mat& m) { return {m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)}; }

// Where a registration puts the frame's centre, against the truth.
double centre_error(const Eigen::Matrix3d& registered, const cv::Matx33d& truth, cv::Size size) {
    const cv::Vec3d c((size.width - 1) / 2.0, (size.height - 1) / 2.0, 1);
    const cv::Vec3d t = truth * c;
    const Eigen::Vector3d r = registered * Eigen::Vector3d(c[0], c[1], 1);
    return std::hypot(t[0] / t[2] - r.x() / r.z(), t[1] / t[2] - r.y() / r.z());
}

// Frames 134 and 135 of the document's swing: with the whole homography at
// every level the alignment of the lines of text slides a line along (27
// pixels off at the centre, its residual low enough to pass), and every
// frame kept was lost there; the coarsest level's affine change aligns
// them (what PulseSearch tries where the whole homography fails).
TEST(RegistrationScenes, ADocumentsLinesAlignedAffineAtCoarseLevels) {
    const bench::Scene scene;
    const cv::Size res(640, 480);
    const sim::CameraModel camera{res, scene.hfov_deg};
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::document, scene.screen.pixels, 7);
    const auto rs = bench::pulsing_recipes(scene, sim::ScreenKind::document, 150, 1);
    const bench::FrameRecipe& a = rs.at(134);
    const bench::FrameRecipe& b = rs.at(135);
    const bench::Frame from = bench::shoot(scene, a, screen, res), to = bench::shoot(scene, b, screen, res);
    const cv::Matx33d truth = sim::screen_to_image(scene.screen, camera, b.pose) *
                              sim::screen_to_image(scene.screen, camera, a.pose).inv();
    const FramePyramid from_levels(view(from.grey)), to_levels(view(to.grey));
    RegistrationOptions affine;
    affine.affine_coarse = true;
    const FrameRegistration r = register_frames(from_levels, to_levels, Eigen::Matrix3d::Identity(), affine);
    EXPECT_TRUE(r.registered) << "residual " << r.residual;
    EXPECT_LT(centre_error(r.homography, truth, res), 0.5);
    const FrameRegistration f = register_frames(from_levels, to_levels);
    EXPECT_GT(centre_error(f.homography, truth, res), 10) << "the whole homography at every level: a line along";
}

// The same frames in a pulse search, from the frame before them: the whole
// homography's registration of frame 135 is refused (the motion check), and
// the search aligns it again with the coarsest level affine
// (PulseSearchOptions::affine_retry) instead of starting over.
TEST(RegistrationScenes, APulseSearchAlignsADocumentAgainAffineWhereTheWholeHomographyFails) {
    const bench::Scene scene;
    const cv::Size res(640, 480);
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::document, scene.screen.pixels, 7);
    const auto rs = bench::pulsing_recipes(scene, sim::ScreenKind::document, 150, 1);
    std::vector<cv::Mat> frames;
    for (int i = 132; i <= 135; ++i) frames.push_back(bench::shoot(scene, rs.at(static_cast<std::size_t>(i)), screen, res).grey);
    for (const bool retry : {true, false}) {
        PulseSearchOptions options;
        options.affine_retry = retry;
        options.detail_retry = false;  // which aligns it too
        PulseSearch search(options);
        for (const cv::Mat& m : frames) search.add(view(m));
        EXPECT_EQ(search.registration_losses(), retry ? 0 : 1) << (retry ? "aligned again" : "the whole homography");
        EXPECT_EQ(search.frames(), retry ? 4 : 1);
    }
}

// Frames 16 and 17 of the dark code's swing: a lamp's glare lies over the
// second (the everyday degradations' reflection, brighter than the dark
// screen's text by far), which one grey-level offset for the whole frame
// cannot follow: aligned on the frames' grey levels the registration ended
// 22 pixels off at the centre, and every frame kept was lost. Aligned on
// their detail (each level less its local mean) it is right.
TEST(RegistrationScenes, ALampsGlareOverDarkCodeAlignedOnTheFramesDetail) {
    const bench::Scene scene;
    const cv::Size res(640, 480);
    const sim::CameraModel camera{res, scene.hfov_deg};
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::code_dark, scene.screen.pixels, 7);
    const auto rs = bench::pulsing_recipes(scene, sim::ScreenKind::code_dark, 150, 1);
    const bench::FrameRecipe& a = rs.at(16);
    const bench::FrameRecipe& b = rs.at(17);
    ASSERT_EQ(a.degradation.glare, 0);
    ASSERT_GT(b.degradation.glare, 0);
    const bench::Frame from = bench::shoot(scene, a, screen, res), to = bench::shoot(scene, b, screen, res);
    const cv::Matx33d truth = sim::screen_to_image(scene.screen, camera, b.pose) *
                              sim::screen_to_image(scene.screen, camera, a.pose).inv();
    const FramePyramid from_levels(view(from.grey)), to_levels(view(to.grey));
    RegistrationOptions detail;
    detail.detail = true;
    const FrameRegistration r = register_frames(from_levels, to_levels, Eigen::Matrix3d::Identity(), detail);
    EXPECT_TRUE(r.registered) << "residual " << r.residual;
    EXPECT_LT(centre_error(r.homography, truth, res), 0.5);
    const FrameRegistration g = register_frames(from_levels, to_levels);
    EXPECT_TRUE(!g.registered || centre_error(g.homography, truth, res) > 5) << "on the grey levels";
}

// In a pulse search the same frames are kept together (the registration
// aligned again on their detail), but a place found before them is not
// carried through an alignment on the detail alone.
TEST(RegistrationScenes, APulseSearchKeepsFramesAlignedOnTheirDetailButCarriesNoPlaceThrough) {
    const bench::Scene scene;
    const cv::Size res(640, 480);
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::code_dark, scene.screen.pixels, 7);
    const auto rs = bench::pulsing_recipes(scene, sim::ScreenKind::code_dark, 150, 1);
    std::vector<cv::Mat> frames;
    for (int i = 14; i <= 17; ++i) frames.push_back(bench::shoot(scene, rs.at(static_cast<std::size_t>(i)), screen, res).grey);
    PulseSearch search;
    for (std::size_t i = 0; i + 1 < frames.size(); ++i) search.add(view(frames[i]));
    Detection found;
    found.found = true;
    found.aim_image = {320, 240};
    found.aim_field = {30, 20};
    found.image_to_field << 0.1, 0, -2, 0, 0.1, -4, 0, 0, 1;
    search.found_elsewhere(found);
    ASSERT_TRUE(search.carried({320, 240}).has_value());
    search.add(view(frames.back()));
    EXPECT_EQ(search.registration_losses(), 0);
    EXPECT_EQ(search.frames(), 4);
    EXPECT_TRUE(search.last_registration().on_detail);
    EXPECT_FALSE(search.carried({320, 240}).has_value()) << "carried through an alignment on the detail";
}

}  // namespace registration_scenes
