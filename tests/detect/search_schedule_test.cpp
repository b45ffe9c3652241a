// The search spread over a video's frames (search_plan.hpp): a round of the
// schedule covers the whole search, a frame without a lock runs one part of
// it, and a field only a fallback finds is still found within a round.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"

namespace {

using namespace umf;

GreyView view_of(const cv::Mat& grey) {
    return {grey.data, grey.cols, grey.rows, static_cast<std::ptrdiff_t>(grey.step)};
}

TEST(SearchSchedule, ARoundCoversTheWholeSearchOnePartAFrame) {
    SearchPlan all{0, 0, 0, 0, 0, 0};
    for (int k = 0; k < kSearchScheduleFrames; ++k) {
        const SearchPlan p = search_schedule(k);
        const unsigned masks[] = {p.scans, p.smaller_scans, p.lattices, p.double_scans, p.smoothed_scans,
                                  p.smoothed_smaller_scans};
        int parts = 0;
        for (unsigned m : masks) parts += m != 0;
        EXPECT_EQ(parts, 1) << "frame " << k << " of the round";
        if (k % 2 == 0) {
            EXPECT_EQ(p.scans, kFirstScan) << "frame " << k << ": the first scan on even frames";
        }
        all.scans |= p.scans, all.smaller_scans |= p.smaller_scans, all.lattices |= p.lattices;
        all.double_scans |= p.double_scans, all.smoothed_scans |= p.smoothed_scans;
        all.smoothed_smaller_scans |= p.smoothed_smaller_scans;
        // Round after round, from any frame.
        const SearchPlan next = search_schedule(k + kSearchScheduleFrames);
        EXPECT_EQ(next.scans, p.scans);
        EXPECT_EQ(next.lattices, p.lattices);
    }
    for (unsigned m : {all.scans, all.smaller_scans, all.lattices, all.double_scans, all.smoothed_scans,
                       all.smoothed_smaller_scans})
        EXPECT_EQ(m, ~0u);
}

TEST(SearchSchedule, APhotosSearchIsTheFirstScanThenEveryPartOnce) {
    const FullSearch plans = full_search();
    EXPECT_EQ(plans[0].scans, kFirstScan);
    for (const auto& order : {kPartOrder, kPartOrderNearPrior}) {
        std::vector<int> parts(order.begin(), order.end());
        std::sort(parts.begin(), parts.end());
        for (int k = 0; k < kSearchParts; ++k) EXPECT_EQ(parts[static_cast<std::size_t>(k)], k);
    }
    for (std::size_t k = 1; k < plans.size(); ++k) {
        const SearchPlan expected = search_part(kPartOrder[k - 1]);
        EXPECT_EQ(plans[k].scans, expected.scans);
        EXPECT_EQ(plans[k].smaller_scans, expected.smaller_scans);
        EXPECT_EQ(plans[k].lattices, expected.lattices);
        EXPECT_EQ(plans[k].double_scans, expected.double_scans);
        EXPECT_EQ(plans[k].smoothed_scans, expected.smoothed_scans);
        EXPECT_EQ(plans[k].smoothed_smaller_scans, expected.smoothed_smaller_scans);
    }
}

// The tuning set's tiny modules (3-4 pixels at 640 x 480): the first scan
// misses most of them, the lattice finds them.
TEST(SearchSchedule, ATrackerWithoutALockSpreadsTheSearchAndStillFindsWhatOnlyAFallbackFinds) {
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const Detector detector(field);
    const bench::Scene scene;
    const sim::FieldPlacement placement{{0, 0}, scene.module_px};
    std::vector<cv::Mat> bare, with_field;
    for (auto kind : sim::kAllScreenKinds) {
        bare.push_back(sim::make_screen(kind, scene.screen.pixels, 7));
        with_field.push_back(sim::mix_field(bare.back(), field, placement, 0.3));
    }
    const auto recipes = bench::category_recipes(scene, bench::Category::tiny, 20, 1);
    const cv::Size vga(640, 480);
    const bench::FrameRecipe* chosen = nullptr;
    bench::Frame frame;
    Detection full;
    for (const auto& r : recipes) {
        frame = bench::shoot(scene, r, with_field[static_cast<std::size_t>(r.screen)], vga);
        if (!frame.centre_on_screen) continue;
        const GreyView v = view_of(frame.grey);
        const Eigen::Vector2d centre(v.width / 2.0, v.height / 2.0);
        if (detector.detect(v, centre, nullptr, search_schedule(0)).found) continue;
        full = detector.detect(v);
        if (full.found) {
            chosen = &r;
            break;
        }
    }
    ASSERT_NE(chosen, nullptr) << "no tiny frame that only a fallback finds";
    const bench::Frame empty = bench::shoot(scene, *chosen, bare[static_cast<std::size_t>(chosen->screen)], vga);

    // The camera starts on the screen without the field (the whole search),
    // then keeps seeing it for a round without a lock: one part a frame.
    TrackerOptions spread;
    spread.spread_search = true;
    Tracker tracker(detector, spread);
    const TrackResult first = tracker.update(view_of(empty.grey));
    EXPECT_FALSE(first.detection.found);
    long most_pixels = 0;
    for (int k = 1; k < kSearchScheduleFrames; ++k) {
        const TrackResult r = tracker.update(view_of(empty.grey));
        EXPECT_FALSE(r.detection.found);
        EXPECT_LT(r.detection.pixels_visited, first.detection.pixels_visited) << "frame " << k;
        most_pixels = std::max(most_pixels, r.detection.pixels_visited);
    }
    std::cout << "[ measure  ] without the field: the whole search read " << first.detection.pixels_visited
              << " pixels, a part at most " << most_pixels << "\n";

    // The field comes into view: found within a round, no frame before the
    // lock reading as much as the whole search.
    Tracker fresh(detector, spread);
    fresh.update(view_of(empty.grey));
    int frames = 0;
    TrackResult r;
    while (frames < kSearchScheduleFrames) {
        r = fresh.update(view_of(frame.grey));
        ++frames;
        if (r.state == TrackState::locked) break;
        EXPECT_LT(r.detection.pixels_visited, first.detection.pixels_visited) << "frame " << frames;
    }
    ASSERT_EQ(r.state, TrackState::locked) << "not found in a round of the schedule";
    const double error = cv::norm(cv::Point2d(r.aim_field.x(), r.aim_field.y()) * scene.module_px -
                                  frame.centre_screen_px) / scene.module_px;
    EXPECT_LT(error, 0.5);
    std::cout << "[ measure  ] a tiny frame only a fallback finds: locked on frame " << frames << " of the round\n";
}

}  // namespace
