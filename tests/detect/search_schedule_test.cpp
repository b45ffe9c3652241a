// The search spread over a video's frames (search_plan.hpp): a round of the
// schedule covers the whole search, a frame without a lock runs the first
// scan and a share of the rest within a budget, and a field only a fallback
// finds is still found within a round.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/detect/scene_screens.hpp"

namespace {

using namespace umf;

GreyView view_of(const cv::Mat& grey) {
    return {grey.data, grey.cols, grey.rows, static_cast<std::ptrdiff_t>(grey.step)};
}

// Which parts a plan names (each part's masks are its own).
std::vector<int> parts_of(const SearchPlan& p) {
    std::vector<int> out;
    for (int k = 0; k < kSearchParts; ++k) {
        const SearchPlan q = search_part(k);
        if ((p.scans & q.scans) || (p.smaller_scans & q.smaller_scans) || (p.lattices & q.lattices) ||
            (p.double_scans & q.double_scans) || (p.smoothed_scans & q.smoothed_scans) ||
            (p.smoothed_smaller_scans & q.smoothed_smaller_scans))
            out.push_back(k);
    }
    return out;
}

TEST(SearchSchedule, ARoundCoversTheWholeSearchInSharesWithinTheBudget) {
    EXPECT_EQ(schedule_frames(0), kRoundPieces) << "no budget: one piece a frame";
    EXPECT_EQ(schedule_frames(1000), 1) << "a budget for everything: one frame";
    // Every piece of every part once a round: piece 0 of each part, piece 1
    // of each part that searches edgels (the first scan runs on every frame).
    std::vector<std::pair<int, int>> expected;
    for (int piece = 0; piece < kPiecesOfAPart; ++piece)
        for (int part : kPartOrder)
            if (piece == 0 || search_part(part).lattices == 0) expected.emplace_back(part, piece);
    ASSERT_EQ(expected.size(), static_cast<std::size_t>(kRoundPieces));
    for (const double budget : {0.0, 2.0, 3.0, 8.0, 1000.0}) {
        const int frames = schedule_frames(budget);
        std::vector<std::pair<int, int>> seen;
        for (int k = 0; k < frames; ++k) {
            const ScheduledSearch s = search_schedule(k, budget);
            ASSERT_GE(s.count, 2u) << "the first scan and a piece at least";
            EXPECT_EQ(s.plans[0].scans, kFirstScan);
            EXPECT_EQ(s.plans[0].edgel_sets, kEveryEdgelSet);
            EXPECT_FALSE(s.plans[0].second_pass);
            EXPECT_EQ(s.plans[0].smaller_scans | s.plans[0].lattices | s.plans[0].double_scans |
                          s.plans[0].smoothed_scans | s.plans[0].smoothed_smaller_scans, 0u);
            double cost = 0;
            for (std::size_t i = 1; i < s.count; ++i) {
                const SearchPiece& piece = kSpreadRound[seen.size()];
                EXPECT_EQ(std::make_pair(piece.part, piece.piece), expected[seen.size()]) << "in the round's order";
                seen.emplace_back(piece.part, piece.piece);
                EXPECT_EQ(parts_of(s.plans[i]), std::vector<int>{piece.part});
                EXPECT_EQ(s.plans[i].edgel_sets,
                          piece.piece == 0 ? kFieldLikeEdgels : (kAllEdgels | kOffThinLineEdgels));
                if (piece.piece != 0) {
                    EXPECT_EQ(s.plans[i].lattices, 0u) << "a lattice is in its part's piece 0";
                }
                EXPECT_FALSE(s.plans[i].second_pass);
                cost += piece.cost;
            }
            EXPECT_TRUE(s.count == 2 || cost <= budget) << "budget " << budget << ", frame " << k;
            // Round after round, from any frame.
            const ScheduledSearch next = search_schedule(k + frames, budget);
            ASSERT_EQ(next.count, s.count);
            for (std::size_t i = 0; i < s.count; ++i) EXPECT_EQ(parts_of(next.plans[i]), parts_of(s.plans[i]));
        }
        EXPECT_EQ(seen, expected) << "every piece once a round";
    }
}

// The first scan's two pieces in one call try the same pairs of the same
// labellings in the same order as its first pass (spread_first, less its
// look near the aim first, which searches a part of the frame of its own);
// with the second pass, as the first scan does: the same place, found or
// not, on any frame.
TEST(SearchSchedule, APartsPiecesTogetherAreThePart) {
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const Detector detector(field);
    const bench::Scene scene;
    const sim::FieldPlacement placement{{0, 0}, scene.module_px};
    const cv::Size vga(640, 480);
    int found = 0, compared = 0;
    for (const auto category : {bench::Category::general, bench::Category::ruled, bench::Category::smeared}) {
        for (const auto& r : bench::category_recipes(scene, category, 4, 3)) {
            const cv::Mat screen = sim::make_screen(sim::kAllScreenKinds[static_cast<std::size_t>(r.screen) %
                                                                         sim::kAllScreenKinds.size()],
                                                    scene.screen.pixels, 7);
            for (const double opacity : {0.0, 0.15}) {
                const bench::Frame frame =
                    bench::shoot(scene, r, opacity > 0 ? sim::mix_field(screen, field, placement, opacity) : screen, vga);
                const GreyView v = view_of(frame.grey);
                const Eigen::Vector2d centre(v.width / 2.0, v.height / 2.0);
                SearchPlan pieces[] = {search_piece(first_scan_only(), 0), search_piece(first_scan_only(), 1)};
                pieces[0].lattice_first_if_small = true;  // as spread_first() has it
                SearchPlan with_second_pass[] = {pieces[0], pieces[1]};
                for (SearchPlan& p : with_second_pass) {
                    p.second_pass = true;
                    p.lattice_first_if_small = false;
                }
                SearchPlan whole_frame_first = spread_first();
                whole_frame_first.near_aim_first = false;
                const Detection first_scan = detector.detect(v, centre, nullptr, first_scan_only());
                for (const auto& [whole, pieced] :
                     {std::pair(detector.detect(v, centre, nullptr, whole_frame_first),
                                detector.detect(v, centre, nullptr, std::span<const SearchPlan>(pieces))),
                      std::pair(first_scan,
                                detector.detect(v, centre, nullptr, std::span<const SearchPlan>(with_second_pass)))}) {
                    EXPECT_EQ(pieced.found, whole.found);
                    EXPECT_EQ(pieced.grids_read, whole.grids_read);
                    EXPECT_EQ(pieced.places_checked, whole.places_checked);
                    EXPECT_EQ(pieced.aim_field, whole.aim_field);
                    EXPECT_EQ(pieced.failure, whole.failure);
                }
                ++compared;
                found += first_scan.found;
            }
        }
    }
    EXPECT_GT(found, 0) << "some frames with the field found";
    EXPECT_LT(found, compared) << "and some not";
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
    const test::SceneScreens screens(scene, field, 0.3);
    const auto recipes = bench::category_recipes(scene, bench::Category::tiny, 20, 1);
    const cv::Size vga(640, 480);
    const bench::FrameRecipe* chosen = nullptr;
    bench::Frame frame;
    Detection full;
    for (const auto& r : recipes) {
        frame = bench::shoot(scene, r, screens.with_field_of(r.screen), vga);
        if (!frame.centre_on_screen) continue;
        const GreyView v = view_of(frame.grey);
        const Eigen::Vector2d centre(v.width / 2.0, v.height / 2.0);
        // Not what every frame's first scan finds, even knowing where the
        // field was; and only one share of the round finds it.
        full = detector.detect(v);
        if (!full.found) continue;
        const DetectionPrior prior{full.image_to_field, TrackerOptions{}.search_radius_modules};
        if (detector.detect(v, centre, &prior, spread_first()).found) continue;
        int finding_shares = 0;
        for (int g = 0; g < schedule_frames(TrackerOptions{}.search_budget); ++g) {
            const ScheduledSearch share = search_schedule(g, TrackerOptions{}.search_budget);
            finding_shares += detector.detect(v, centre, &prior, std::span<const SearchPlan>(share.plans.data(), share.count)).found;
        }
        if (finding_shares != 1) continue;
        chosen = &r;
        break;
    }
    ASSERT_NE(chosen, nullptr) << "no tiny frame that one share of the round alone finds";
    const bench::Frame empty = bench::shoot(scene, *chosen, screens.bare_of(chosen->screen), vga);

    // The camera starts on the screen without the field and sees it for a
    // round without a lock: a share a frame, every one of them less than
    // the whole search, from the first frame on.
    const GreyView empty_view = view_of(empty.grey);
    const long whole = detector.detect(empty_view).pixels_visited;
    TrackerOptions spread;
    spread.spread_search = true;
    const int round = schedule_frames(spread.search_budget);
    Tracker tracker(detector, spread);
    long most_pixels = 0;
    for (int k = 0; k < round; ++k) {
        const TrackResult r = tracker.update(empty_view);
        EXPECT_FALSE(r.detection.found);
        EXPECT_LT(r.detection.pixels_visited, whole) << "frame " << k;
        most_pixels = std::max(most_pixels, r.detection.pixels_visited);
    }
    std::cout << "[ measure  ] without the field: the whole search read " << whole << " pixels, a share at most "
              << most_pixels << "\n";

    // The field comes into view: found within a round.
    const GreyView field_view = view_of(frame.grey);
    auto lock_within = [&](Tracker& t, int frames_at_most) {
        for (int k = 1; k <= frames_at_most; ++k)
            if (t.update(field_view).state == TrackState::locked) return k;
        return 0;
    };
    Tracker fresh(detector, spread);
    fresh.update(empty_view);
    const int frames = lock_within(fresh, round);
    ASSERT_GT(frames, 0) << "not found in a round of the schedule";
    const TrackResult r = fresh.update(field_view);
    ASSERT_EQ(r.state, TrackState::locked);
    const double error = cv::norm(cv::Point2d(r.aim_field.x(), r.aim_field.y()) * scene.module_px -
                                  frame.centre_screen_px) / scene.module_px;
    EXPECT_LT(error, 0.5);
    std::cout << "[ measure  ] a tiny frame only a fallback finds: locked on frame " << frames << " of the round\n";

    // Lost for longer than the tracker follows a place (a faint phase of a
    // pulse), then in view again: the share that found it comes again
    // within two frames, not a round later.
    for (int k = 0; k <= spread.follow_frames; ++k) EXPECT_NE(fresh.update(empty_view).state, TrackState::locked);
    EXPECT_GT(lock_within(fresh, 2), 0) << "the share that found the last lock is tried again";

    // The same on a device with no time to spare (TrackerOptions::frame_ms):
    // a step of the round a frame, so found within as many frames as the
    // round has steps; lost and in view again, the step that found it comes
    // again within two frames.
    std::vector<SearchPlan> round_plans{spread_first()};
    for (const SearchPiece& piece : kSpreadRound) round_plans.push_back(piece.plan());
    SearchLimit all;
    all.ms = 1e4;
    detector.detect(empty_view, Eigen::Vector2d(320, 240), nullptr,
                    std::span<const SearchPlan>(round_plans.data(), round_plans.size()), all);
    TrackerOptions held = spread;
    held.frame_ms = 1e-3;
    Tracker slow(detector, held);
    slow.update(empty_view);
    const int frames_held = lock_within(slow, all.steps_run + 1);
    ASSERT_GT(frames_held, 0) << "not found in " << all.steps_run << " steps of the round";
    std::cout << "[ measure  ] held to no time a frame: locked on frame " << frames_held << " (the round has "
              << all.steps_run << " steps)\n";
    for (int k = 0; k <= held.follow_frames; ++k) EXPECT_NE(slow.update(empty_view).state, TrackState::locked);
    EXPECT_GT(lock_within(slow, 2), 0) << "the step that found the last lock is tried again";
}

// Held to the frame's time (TrackerOptions::frame_ms): a device with no
// time to spare runs little of the round a frame, one with time enough the
// whole round on its first frame.
TEST(SearchSchedule, HeldToTheFramesTimeAFrameRunsWhatFits) {
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const Detector detector(field);
    const bench::Scene scene;
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::document, scene.screen.pixels, 7);
    const auto recipes = bench::category_recipes(scene, bench::Category::general, 1, 1);
    const bench::Frame frame = bench::shoot(scene, recipes.front(), screen, cv::Size(640, 480));
    const GreyView v = view_of(frame.grey);
    std::vector<SearchPlan> round_plans{spread_first()};
    for (const SearchPiece& piece : kSpreadRound) round_plans.push_back(piece.plan());
    const long round = detector.detect(v, Eigen::Vector2d(v.width / 2.0, v.height / 2.0), nullptr,
                                       std::span<const SearchPlan>(round_plans.data(), round_plans.size()))
                           .pixels_visited;
    for (const double frame_ms : {1e-3, 1e4}) {
        TrackerOptions o;
        o.spread_search = true;
        o.frame_ms = frame_ms;
        Tracker tracker(detector, o);
        for (int k = 0; k < 4; ++k) {
            const Detection d = tracker.update(v).detection;
            EXPECT_FALSE(d.found);
            if (frame_ms < 1) {
                EXPECT_LT(d.pixels_visited, round / 4) << "frame " << k << ": a step at most";
            } else if (k == 0) {
                EXPECT_EQ(d.pixels_visited, round) << "the whole round on the first frame";
            }
        }
    }
}

}  // namespace
