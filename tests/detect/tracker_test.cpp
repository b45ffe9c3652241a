// The tracker's states and its follow of a prediction, on simulated photos
// (tracker_scenes_test.cpp follows it over video).
#include <gtest/gtest.h>

#include "shared/detect/tracker.hpp"
#include "tests/detect/photo.hpp"

namespace {

using namespace umf;

TEST(Tracker, ReportsLostWithoutAPlaceThenSearchingAfterAReset) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    Tracker tracker(detector);
    const test::Photo seen = test::photograph_field(f, 0.5, 0, 0, 0, 300);
    const test::Photo blank = test::photograph_field(f, 0, 0, 0, 0, 300);
    EXPECT_EQ(tracker.update(seen.view()).state, TrackState::locked);
    const TrackResult second = tracker.update(seen.view());
    EXPECT_EQ(second.state, TrackState::locked);
    EXPECT_TRUE(second.used_prior);
    const TrackResult gone = tracker.update(blank.view());
    EXPECT_EQ(gone.state, TrackState::lost);
    EXPECT_FALSE(gone.detection.found);
    EXPECT_EQ(gone.frames_since_lock, 1);
    tracker.reset();
    EXPECT_EQ(tracker.update(blank.view()).state, TrackState::searching);
}

// A prediction a few modules off must not be "confirmed" at the wrong place.
TEST(Tracker, FollowRefusesAPredictionThatIsOff) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    const test::Photo photo = test::photograph_field(f, 0.4, 10, 5, 30, 300);
    const Detection d = detector.detect(photo.view());
    ASSERT_TRUE(d.found);
    const Eigen::Vector2d centre(320, 240);
    EXPECT_TRUE(detector.follow(photo.view(), centre, d.image_to_field).found);
    for (const auto& [du, dv] : {std::pair{1.0, 0.0}, {0.0, -2.0}, {3.0, 3.0}, {0.5, 0.5}}) {
        Eigen::Matrix3d shifted;
        shifted << 1, 0, du, 0, 1, dv, 0, 0, 1;
        const Detection moved = detector.follow(photo.view(), centre, shifted * d.image_to_field);
        if (moved.found) {
            EXPECT_LT((moved.aim_field - d.aim_field).norm(), 0.2) << du << "," << dv;
        }
    }
}

}  // namespace
