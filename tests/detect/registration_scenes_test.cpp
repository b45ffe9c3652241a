// Frame registration and the pulse search on the pulsing benchmark's own
// frames (the tuning set's swing, tests/bench/scenario.hpp), where a
// failure was seen.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "shared/detect/frame_registration.hpp"
#include "shared/detect/pulse_search.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/detect/photo.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/screen_content.hpp"

namespace registration_scenes {

using namespace umf;

using test::grey_view;

// Where a registration puts the frame's centre, against the truth.
double centre_error(const Eigen::Matrix3d& registered, const cv::Matx33d& truth, cv::Size size) {
    const cv::Vec3d c((size.width - 1) / 2.0, (size.height - 1) / 2.0, 1);
    const cv::Vec3d t = truth * c;
    const Eigen::Vector3d r = registered * Eigen::Vector3d(c[0], c[1], 1);
    return std::hypot(t[0] / t[2] - r.x() / r.z(), t[1] / t[2] - r.y() / r.z());
}

// Frames `first` and first + 1 of a screen kind's swing (the pulsing
// benchmark's tuning videos, without the field) and the true motion between
// them.
struct FramePair {
    cv::Mat from, to;
    cv::Matx33d truth;
    bench::FrameRecipe from_recipe, to_recipe;
};

FramePair frame_pair(sim::ScreenKind kind, int first) {
    const bench::Scene scene;
    const cv::Size res(640, 480);
    const sim::CameraModel camera{res, scene.hfov_deg};
    const cv::Mat screen = sim::make_screen(kind, scene.screen.pixels, 7);
    const auto rs = bench::pulsing_recipes(scene, kind, 150, 1);
    const bench::FrameRecipe& a = rs.at(static_cast<std::size_t>(first));
    const bench::FrameRecipe& b = rs.at(static_cast<std::size_t>(first + 1));
    return {bench::shoot(scene, a, screen, res).grey, bench::shoot(scene, b, screen, res).grey,
            sim::screen_to_image(scene.screen, camera, b.pose) * sim::screen_to_image(scene.screen, camera, a.pose).inv(),
            a, b};
}

// Frames first..last of a screen kind's swing, without the field.
std::vector<cv::Mat> swing_frames(sim::ScreenKind kind, int first, int last) {
    const bench::Scene scene;
    const cv::Mat screen = sim::make_screen(kind, scene.screen.pixels, 7);
    const auto rs = bench::pulsing_recipes(scene, kind, 150, 1);
    std::vector<cv::Mat> frames;
    for (int i = first; i <= last; ++i)
        frames.push_back(bench::shoot(scene, rs.at(static_cast<std::size_t>(i)), screen, cv::Size(640, 480)).grey);
    return frames;
}

// The pair registered with `options`: right within half a pixel at the
// centre. Then registered with the default options: how far off at the centre
// (infinity where not registered).
double registered_right_then_default_off(const FramePair& pair, const RegistrationOptions& options) {
    const cv::Size res(pair.from.cols, pair.from.rows);
    const FramePyramid from_levels(grey_view(pair.from)), to_levels(grey_view(pair.to));
    const FrameRegistration r = register_frames(from_levels, to_levels, Eigen::Matrix3d::Identity(), options);
    EXPECT_TRUE(r.registered) << "residual " << r.residual;
    EXPECT_LT(centre_error(r.homography, pair.truth, res), 0.5);
    const FrameRegistration f = register_frames(from_levels, to_levels);
    return f.registered ? centre_error(f.homography, pair.truth, res) : std::numeric_limits<double>::infinity();
}

// Frames 134 and 135 of the document's swing: with the whole homography at
// every level the alignment of the lines of text slides a line along (27
// pixels off at the centre, its residual low enough to pass), and every
// frame kept was lost there; the coarsest level's affine change aligns
// them (what PulseSearch tries where the whole homography fails).
TEST(RegistrationScenes, ADocumentsLinesAlignedAffineAtCoarseLevels) {
    RegistrationOptions affine;
    affine.affine_coarse = true;
    EXPECT_GT(registered_right_then_default_off(frame_pair(sim::ScreenKind::document, 134), affine), 10)
        << "the whole homography at every level: a line along";
}

// The same frames in a pulse search, from the frame before them: the whole
// homography's registration of frame 135 is refused (the motion check), and
// the search aligns it again with the coarsest level affine
// (PulseSearchOptions::affine_retry) instead of starting over.
TEST(RegistrationScenes, APulseSearchAlignsADocumentAgainAffineWhereTheWholeHomographyFails) {
    const std::vector<cv::Mat> frames = swing_frames(sim::ScreenKind::document, 132, 135);
    for (const bool retry : {true, false}) {
        PulseSearchOptions options;
        options.affine_retry = retry;
        options.detail_retry = false;  // which aligns it too
        PulseSearch search(options);
        for (const cv::Mat& m : frames) search.add(grey_view(m));
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
    const FramePair pair = frame_pair(sim::ScreenKind::code_dark, 16);
    ASSERT_EQ(pair.from_recipe.degradation.glare, 0);
    ASSERT_GT(pair.to_recipe.degradation.glare, 0);
    RegistrationOptions detail;
    detail.detail = true;
    EXPECT_GT(registered_right_then_default_off(pair, detail), 5) << "on the grey levels";
}

// In a pulse search the same frames are kept together (the registration
// aligned again on their detail), and a place found before them is carried
// through an alignment on the detail alone only while the view has come at
// most PulseSearchOptions::detail_carry_modules since it was found.
TEST(RegistrationScenes, APulseSearchKeepsFramesAlignedOnTheirDetailAndCarriesAPlaceOnlyANearWay) {
    const std::vector<cv::Mat> frames = swing_frames(sim::ScreenKind::code_dark, 14, 17);
    const Eigen::Vector2d centre(320, 240);
    Detection found;
    found.found = true;
    found.aim_image = centre;
    found.aim_field = {30, 20};
    found.image_to_field << 0.1, 0, -2, 0, 0.1, -4, 0, 0, 1;
    // The way the view comes over the field through the last frame: read
    // with no bound, then used to set one either side of it.
    auto run = [&](double bound) {
        PulseSearchOptions options;
        options.detail_carry_modules = bound;
        auto search = std::make_unique<PulseSearch>(options);
        for (std::size_t i = 0; i + 1 < frames.size(); ++i) search->add(grey_view(frames[i]));
        search->found_elsewhere(found);
        EXPECT_TRUE(search->carried(centre).has_value());
        search->add(grey_view(frames.back()));
        EXPECT_EQ(search->registration_losses(), 0);
        EXPECT_EQ(search->frames(), 4);
        EXPECT_TRUE(search->last_registration().on_detail);
        return search;
    };
    const auto unbounded = run(1e9);
    ASSERT_TRUE(unbounded->carry(centre).has_value());
    const double way = unbounded->carry(centre)->travel;
    EXPECT_GT(way, 0.05) << "the view moved";
    EXPECT_TRUE(run(way * 1.5)->carried(centre).has_value()) << "within the bound";
    EXPECT_FALSE(run(way * 0.5)->carried(centre).has_value()) << "beyond it";
    EXPECT_FALSE(run(0)->carried(centre).has_value()) << "0: carried through no alignment on the detail";
    EXPECT_LE(way, PulseSearchOptions{}.detail_carry_modules) << "a frame's way is within the default";
}

}  // namespace registration_scenes
