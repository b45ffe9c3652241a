// The first scan near the aim (SearchPlan::near_aim_first): the part of the
// frame around the aim, half its width and height, searched on its own
// before the whole frame. Where the field fills the middle of the view it is
// found there, at the same place, for a fraction of the pixels; where the
// middle holds too little of it, the whole frame's search still finds it,
// in a tracker's first scan at half size where the frame is large, on its
// field-like edgels alone where they stand apart.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/search_plan.hpp"
#include "shared/detect/tracker.hpp"
#include "tests/detect/photo.hpp"

namespace {

using namespace umf;

DetectorOptions never_near_aim() {
    DetectorOptions o;
    o.near_aim_part = 0;
    return o;
}

DetectorOptions never_halved() {
    DetectorOptions o;
    o.whole_frame_half_min_side = 0;
    return o;
}

class NearAim : public ::testing::Test {
protected:
    Field field_ = test::shipped_field("b4-64x36.json");
    Detector detector_{field_};
    Detector whole_frame_{field_, never_near_aim()};
    // A document under the field, photographed at a slant.
    test::Photo photo_ = test::photograph_field(field_, 0.3, 10, 5, 20, 300, sim::ScreenKind::document);
};

TEST_F(NearAim, TheMiddleOfTheViewFindsTheSamePlaceForFewerPixels) {
    const Detection near = detector_.detect(photo_.view());
    const Detection whole = whole_frame_.detect(photo_.view());
    ASSERT_TRUE(near.found) << near.failure;
    ASSERT_TRUE(whole.found) << whole.failure;
    EXPECT_TRUE(near.from_near_aim);
    EXPECT_FALSE(whole.from_near_aim);
    EXPECT_EQ(near.size_scale, 1);
    EXPECT_NEAR(near.aim_image.x(), whole.aim_image.x(), 1e-9) << "the aim in the frame's coordinates";
    EXPECT_NEAR(near.aim_image.y(), whole.aim_image.y(), 1e-9);
    EXPECT_LT((near.aim_field - whole.aim_field).norm(), 0.05) << "modules";
    // The homography carried back to the frame: a point far from the part
    // maps where the whole frame's map takes it, within a module.
    const Eigen::Vector3d corner(20, 20, 1);
    const Eigen::Vector3d a = near.image_to_field * corner, b = whole.image_to_field * corner;
    EXPECT_LT((a.hnormalized() - b.hnormalized()).norm(), 1.0) << "modules, at the frame's corner";
    EXPECT_LT(near.pixels_visited, whole.pixels_visited / 2);
}

TEST_F(NearAim, ANearScreensLargeModulesAreLeftToTheWholeFrame) {
    // At 9 cm the middle of the view holds too few modules for a place.
    const test::Photo near_screen = test::photograph_field(field_, 0.3, 10, 5, 20, 90, sim::ScreenKind::document);
    const Detection near = detector_.detect(near_screen.view());
    const Detection whole = whole_frame_.detect(near_screen.view());
    ASSERT_TRUE(whole.found) << whole.failure;
    ASSERT_TRUE(near.found) << near.failure;
    EXPECT_FALSE(near.from_near_aim);
    EXPECT_LT((near.aim_field - whole.aim_field).norm(), 1e-9) << "the whole frame's own search";
    EXPECT_GT(near.pixels_visited, whole.pixels_visited) << "the middle was scanned first";
}

// A tracker's first scan and a photo's; near a prior (a tracker that lost
// its lock) the frame's own size first, as the other parts there.
TEST_F(NearAim, ALargeFramesWholeFrameIsSearchedAtHalfSizeInTheFirstScan) {
    const Detector own_size(field_, never_halved());
    for (const cv::Size resolution : {cv::Size(1280, 720), cv::Size(640, 480)}) {
        const test::Photo near_screen =
            test::photograph_field(field_, 0.3, 10, 5, 20, 90, sim::ScreenKind::document, resolution);
        const Eigen::Vector2d aim(resolution.width / 2.0, resolution.height / 2.0);
        const Detection d = detector_.detect(near_screen.view(), aim, nullptr, spread_first());
        const Detection photo = detector_.detect(near_screen.view(), aim);
        const Detection own = own_size.detect(near_screen.view(), aim, nullptr, spread_first());
        ASSERT_TRUE(d.found) << resolution << " " << d.failure;
        ASSERT_TRUE(photo.found) << resolution << " " << photo.failure;
        ASSERT_TRUE(own.found) << resolution << " " << own.failure;
        EXPECT_FALSE(d.from_near_aim) << resolution;
        EXPECT_EQ(own.size_scale, 1) << resolution;
        EXPECT_LT((d.aim_field - own.aim_field).norm(), 0.1) << resolution << ", modules";
        EXPECT_LT((photo.aim_field - own.aim_field).norm(), 0.1) << resolution << ", modules";
        // 720 rows keep 360 at half size, 480 would keep only 240.
        const double halved = resolution.height == 720 ? 0.5 : 1;
        EXPECT_EQ(d.size_scale, halved) << resolution;
        EXPECT_EQ(photo.size_scale, halved) << resolution;
        DetectionPrior prior;
        prior.image_to_field = own.image_to_field;
        const Detection near_prior = detector_.detect(near_screen.view(), aim, &prior);
        ASSERT_TRUE(near_prior.found) << resolution << " " << near_prior.failure;
        EXPECT_EQ(near_prior.size_scale, 1) << resolution;
    }
}

// The whole frame's first scan after the part around the aim: its
// field-like edgels alone where they stand apart from the others
// (SearchPlan::whole_frame_field_like_alone), as in every frame of a
// tracker without a lock and in a photo's first scan. A document's lines
// give all edgels' grids there, each read in vain.
TEST_F(NearAim, TheWholeFramesFieldLikeEdgelsAreSearchedAlone) {
    SearchPlan every_set = spread_first();
    every_set.whole_frame_field_like_alone = false;
    ASSERT_TRUE(spread_first().whole_frame_field_like_alone);
    ASSERT_TRUE(full_search()[0].whole_frame_field_like_alone);
    for (const cv::Size resolution : {cv::Size(640, 480), cv::Size(1280, 720)}) {
        const Eigen::Vector2d aim(resolution.width / 2.0, resolution.height / 2.0);
        const test::Photo bare =
            test::photograph_field(field_, 0, 10, 5, 20, 300, sim::ScreenKind::document, resolution);
        const Detection alone = detector_.detect(bare.view(), aim, nullptr, spread_first());
        const Detection all = detector_.detect(bare.view(), aim, nullptr, every_set);
        EXPECT_FALSE(alone.found) << resolution;
        EXPECT_FALSE(all.found) << resolution;
        EXPECT_LT(alone.grids_read, all.grids_read) << resolution;
        // Where the middle holds too little of the field, the whole frame's
        // field-like edgels find it.
        const test::Photo near_screen =
            test::photograph_field(field_, 0.3, 10, 5, 20, 90, sim::ScreenKind::document, resolution);
        const Detection found = detector_.detect(near_screen.view(), aim, nullptr, spread_first());
        const Detection found_all = detector_.detect(near_screen.view(), aim, nullptr, every_set);
        ASSERT_TRUE(found.found) << resolution << " " << found.failure;
        ASSERT_TRUE(found_all.found) << resolution << " " << found_all.failure;
        EXPECT_FALSE(found.from_near_aim) << resolution;
        EXPECT_LT((found.aim_field - found_all.aim_field).norm(), 1e-9) << resolution << ", modules";
    }
}

TEST_F(NearAim, ATrackersFirstLockComesFromTheMiddle) {
    TrackerOptions o;
    o.spread_search = true;
    o.frame_ms = 16;
    Tracker tracker(detector_, o);
    const TrackResult r = tracker.update(photo_.view());
    ASSERT_EQ(r.state, TrackState::locked) << r.detection.failure;
    EXPECT_TRUE(r.detection.from_near_aim);
}

TEST_F(NearAim, ImagesOfAFewPixelsHaveNoPartToSearch) {
    std::vector<std::uint8_t> px(32 * 32, 128);
    for (int side = 1; side <= 32; ++side) {
        const Detection d = detector_.detect(GreyView{px.data(), side, side, side});
        EXPECT_FALSE(d.found) << side;
        EXPECT_FALSE(d.from_near_aim) << side;
    }
    // An aim far off the frame: the part is the frame's corner nearest it,
    // read within the frame (the sanitizer build checks the reads).
    const Eigen::Vector2d off(-1e6, 1e6);
    const Detection far_aim = detector_.detect(photo_.view(), off);
    const Detection far_aim_whole = whole_frame_.detect(photo_.view(), off);
    EXPECT_EQ(far_aim.found, far_aim_whole.found);
    if (far_aim.found) {
        EXPECT_EQ(far_aim.aim_image, off);
    }
}

TEST_F(NearAim, NotOnAScreenWithoutTheField) {
    const test::Photo bare = test::photograph_field(field_, 0, 10, 5, 20, 300, sim::ScreenKind::document);
    const Detection d = detector_.detect(bare.view());
    EXPECT_FALSE(d.found);
    EXPECT_FALSE(d.from_near_aim);
}

// The second pass takes up each first-pass search's later pairs of
// labellings by the search's number, so it must run the same searches in
// the same order, the part around the aim and the half-size whole frame
// included: then every search tries each of its pairs once over the two
// passes, and a frame without the field has as many grids read as in one
// pass that tries every pair at once. (The second pass once left the part
// around the aim out, as the first pass's later parts had made the frame's
// own scans, and its searches took up other searches' labellings: at
// 640 x 480 here 334 grids were read against one pass's 420.)
TEST_F(NearAim, TheSecondPassTakesUpEachSearchsOwnLabellings) {
    DetectorOptions every_pair_at_once;
    every_pair_at_once.first_pass_pairs = 0;
    const Detector one_pass(field_, every_pair_at_once);
    for (const cv::Size resolution : {cv::Size(640, 480), cv::Size(1280, 720)}) {
        const test::Photo bare =
            test::photograph_field(field_, 0, 10, 5, 20, 300, sim::ScreenKind::document, resolution);
        const Detection two = detector_.detect(bare.view());
        const Detection one = one_pass.detect(bare.view());
        EXPECT_FALSE(two.found) << resolution;
        EXPECT_FALSE(one.found) << resolution;
        EXPECT_GT(two.grids_read, 0) << resolution;
        EXPECT_EQ(two.grids_read, one.grids_read) << resolution;
    }
}

}  // namespace
