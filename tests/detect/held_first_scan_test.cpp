// A tracker held to its frame's time (TrackerOptions::frame_ms) holds the
// first scan too: the part around the aim on every frame, the whole frame's
// searches a step a frame where there is no time for more, taken up where
// the last frame stopped; a lock they found is retried at the step that
// found it, as a lock the round found is retried at its piece.
#include <gtest/gtest.h>

#include <iostream>
#include <vector>

#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/detect/scene_screens.hpp"

namespace {

using namespace umf;

GreyView view_of(const cv::Mat& grey) {
    return {grey.data, grey.cols, grey.rows, static_cast<std::ptrdiff_t>(grey.step)};
}

// The tuning set's pixel_grid category (the screen's own pixel grid under
// the field): in some frames the field is found by the whole frame's later
// searches, where the part around the aim and the whole frame's field-like
// edgels find nothing (as a ruled page's faint field is found off its
// rules, the whole frame's last search).
TEST(HeldFirstScan, ALockTheWholeFramesLaterSearchFoundIsRetriedThere) {
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const Detector detector(field);
    const bench::Scene scene;
    const test::SceneScreens screens(scene, field, 0.3);
    const cv::Size vga(640, 480);
    bench::Frame frame, empty;
    int found_step = -1;
    for (const auto& r : bench::category_recipes(scene, bench::Category::pixel_grid, 20, 1)) {
        frame = bench::shoot(scene, r, screens.with_field_of(r.screen), vga);
        if (!frame.centre_on_screen) continue;
        const GreyView v = view_of(frame.grey);
        SearchLimit all;
        all.ms = 1e4;
        all.first_min_steps = kFirstStepsEveryFrame;
        const SearchPlan first = spread_first();
        const Detection d = detector.detect(v, Eigen::Vector2d(v.width / 2.0, v.height / 2.0), nullptr,
                                            std::span<const SearchPlan>(&first, 1), all);
        // Past the whole frame's first two steps (the lattice's, counted
        // where it does not run, and the field-like edgels').
        if (d.found && all.found_plan == 0 && all.found_step >= kFirstStepsEveryFrame + 2) {
            found_step = all.found_step;
            empty = bench::shoot(scene, r, screens.bare_of(r.screen), vga);
            break;
        }
    }
    ASSERT_GE(found_step, 0) << "no frame that the whole frame's later searches alone find";

    // No time to spare: a frame searches the part around the aim and one
    // step more, so the whole frame's searches take a frame each.
    TrackerOptions held;
    held.spread_search = true;
    held.frame_ms = 1e-3;
    held.hold_first_scan = true;
    Tracker tracker(detector, held);
    const GreyView field_view = view_of(frame.grey), empty_view = view_of(empty.grey);
    auto lock_within = [&](int frames_at_most) {
        for (int k = 1; k <= frames_at_most; ++k)
            if (tracker.update(field_view).state == TrackState::locked) return k;
        return 0;
    };
    const int first_lock = lock_within(found_step - kFirstStepsEveryFrame + 1);
    ASSERT_GT(first_lock, 0) << "the whole frame's searches a step a frame";
    EXPECT_GT(first_lock, 1) << "not on the first frame: the step that finds it is not the whole frame's first";
    std::cout << "[ measure  ] found by the first scan's step " << found_step << "; locked on frame " << first_lock
              << "\n";

    // Lost for longer than the tracker follows a place (a faint phase of a
    // pulse), for as many frames again as the whole frame's searches take,
    // then in view again: the step that found it comes again within two
    // frames, wherever the searches of the frames without it had got to.
    for (int lost = held.follow_frames + 1; lost <= held.follow_frames + 4; ++lost) {
        for (int k = 0; k < lost; ++k) EXPECT_NE(tracker.update(empty_view).state, TrackState::locked);
        EXPECT_GT(lock_within(2), 0) << "lost for " << lost << " frames: the step that found the last lock is tried again";
    }
}

}  // namespace
