// A search held to a time limit (search_plan.hpp's SearchLimit): without
// the time running out it is the search it limits; with no time at all it
// runs the first scan and the steps it owes; taken up again
// where it stopped, it runs every step of the round once, and of the first
// scan's whole frame where that is held too. Times here are 0
// or 10 s, so that what runs does not depend on the machine's speed.
#include <gtest/gtest.h>

#include <iostream>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/detect/photo.hpp"

namespace {

using namespace umf;

constexpr double kNoTime = 0;
constexpr double kAllTheTime = 1e4;

// The first scan and the whole round from `first_piece` on.
std::vector<SearchPlan> round_from(int first_piece) {
    std::vector<SearchPlan> plans{spread_first()};
    for (int k = first_piece; k < kRoundPieces; ++k) plans.push_back(kSpreadRound[static_cast<std::size_t>(k)].plan());
    return plans;
}

// A document on the screen without the field, photographed at a slant.
class SearchLimitOnAScreen : public ::testing::Test {
protected:
    Detection detect(const std::vector<SearchPlan>& plans, SearchLimit* limit = nullptr) const {
        const GreyView v = photo_.view();
        const Eigen::Vector2d centre(v.width / 2.0, v.height / 2.0);
        const std::span<const SearchPlan> span(plans.data(), plans.size());
        return limit ? detector_.detect(v, centre, nullptr, span, *limit) : detector_.detect(v, centre, nullptr, span);
    }

    Field field_ = test::shipped_field("b4-64x36.json");
    Detector detector_{field_};
    test::Photo photo_ = test::photograph_field(field_, 0, 10, 5, 20, 300, sim::ScreenKind::document);
};

TEST_F(SearchLimitOnAScreen, WithTimeEnoughItIsTheSearchItLimits) {
    const std::vector<SearchPlan> plans = round_from(0);
    const Detection whole = detect(plans);
    SearchLimit limit;
    limit.ms = kAllTheTime;
    const Detection limited = detect(plans, &limit);
    EXPECT_FALSE(whole.found) << "the screen without the field";
    EXPECT_EQ(limited.found, whole.found);
    EXPECT_EQ(limited.grids_read, whole.grids_read);
    EXPECT_EQ(limited.pixels_visited, whole.pixels_visited);
    EXPECT_EQ(limited.failure, whole.failure);
    EXPECT_EQ(limit.plans_done, kRoundPieces) << "every piece of the round ran to its end";
    EXPECT_GT(limit.steps_run, kRoundPieces) << "most pieces search more than one edgel set or scan";
    EXPECT_EQ(limit.found_plan, -1);
}

TEST_F(SearchLimitOnAScreen, WithNoTimeOnlyTheFirstScanRuns) {
    const std::vector<SearchPlan> plans = round_from(3);
    SearchLimit limit;
    limit.ms = kNoTime;
    limit.skip_steps = 1;
    const Detection limited = detect(plans, &limit);
    const Detection first_scan = detect({spread_first()});
    EXPECT_FALSE(limited.found);
    EXPECT_EQ(limit.steps_run, 0) << "no step of the round";
    EXPECT_EQ(limit.plans_done, 0);
    EXPECT_EQ(limit.steps_into_next, 1) << "the round stays where it was";
    EXPECT_EQ(limited.grids_read, first_scan.grids_read) << "the first scan whole";
    EXPECT_EQ(limited.pixels_visited, first_scan.pixels_visited);
}

// A step owed a frame, again and again, each call taking the round up
// where the last one stopped: each step of the round runs once, in order,
// and the round ends after as many calls as it has steps.
TEST_F(SearchLimitOnAScreen, TakenUpWhereItStoppedTheRoundRunsEveryStepOnce) {
    SearchLimit all;
    all.ms = kAllTheTime;
    detect(round_from(0), &all);
    const int round_steps = all.steps_run;

    int piece = 0, step = 0, calls = 0, steps = 0;
    long pixels = 0;
    while (piece < kRoundPieces && calls < 10 * round_steps) {
        SearchLimit owed;
        owed.ms = kNoTime;
        owed.min_steps = 1;
        owed.skip_steps = step;
        const Detection d = detect(round_from(piece), &owed);
        ++calls;
        ASSERT_LE(owed.steps_run, 1) << "one step owed, none more in no time";
        steps += owed.steps_run;
        pixels += d.pixels_visited;
        if (owed.plans_done == 0) {
            EXPECT_EQ(owed.steps_run, 1) << "piece " << piece << ": a step owed is a step run";
            EXPECT_EQ(owed.steps_into_next, step + 1) << "piece " << piece << ": on from the step after it";
        }
        step = owed.steps_into_next;
        piece += owed.plans_done;
    }
    EXPECT_EQ(piece, kRoundPieces) << "the round ended";
    EXPECT_EQ(steps, round_steps) << "no step left out, none run twice";
    EXPECT_EQ(calls, round_steps);
    std::cout << "[ measure  ] a round of " << round_steps << " steps; " << pixels << " pixels read over its "
              << calls << " calls\n";
}

// The first scan held too (a tracker held to its frame's time): the part
// around the aim whatever the time, then the whole frame's searches a step
// a call, each call taking them up where the last one stopped, each once;
// a call with the part around the aim alone owes its step to the round.
TEST_F(SearchLimitOnAScreen, TheFirstScanHeldTooRunsAroundTheAimThenAStepACall) {
    constexpr int kAroundTheAim = kFirstStepsEveryFrame;  // the part around the aim: its lattice cue and edgel sets
    SearchLimit all;
    all.ms = kAllTheTime;
    all.first_min_steps = kAroundTheAim;
    const Detection whole_first_scan = detect(round_from(0), &all);
    const int held = all.first_held_steps_run;
    EXPECT_GE(held, 3) << "the whole frame's three edgel sets";

    int from = 0, calls = 0, run = 0;
    do {
        SearchLimit owed;
        owed.ms = kNoTime;
        owed.min_steps = 1;
        owed.first_min_steps = kAroundTheAim;
        owed.first_skip_steps = from;
        const Detection d = detect(round_from(0), &owed);
        ++calls;
        EXPECT_FALSE(d.found);
        EXPECT_EQ(owed.first_held_steps_run, 1) << "call " << calls << ": the step owed is the first scan's";
        EXPECT_EQ(owed.steps_run, 0) << "call " << calls << ": none of the round's";
        EXPECT_EQ(owed.steps_into_next, 0) << "the round stays where it was";
        run += owed.first_held_steps_run;
        ASSERT_TRUE(owed.first_steps_into_next == 0 || owed.first_steps_into_next > from) << "on from where it stopped";
        from = owed.first_steps_into_next;
    } while (from > 0 && calls < 10);
    EXPECT_EQ(run, held) << "every search of the whole frame once";
    EXPECT_EQ(calls, held);

    std::vector<SearchPlan> round_frame = round_from(0);
    round_frame.front().near_aim_alone = true;
    SearchLimit owed;
    owed.ms = kNoTime;
    owed.min_steps = 1;
    owed.first_min_steps = kAroundTheAim;
    const Detection d = detect(round_frame, &owed);
    EXPECT_EQ(owed.first_held_steps_run, 0);
    EXPECT_EQ(owed.steps_run, 1) << "the round's step";
    EXPECT_LT(d.pixels_visited, whole_first_scan.pixels_visited);
}

// The first scan held to a time of its own (SearchLimit::first_ms, a
// tracker's whole time between two camera frames) where the round has none:
// the whole first scan runs, and the step owed is its own, not the round's.
TEST_F(SearchLimitOnAScreen, TheFirstScanHeldToItsOwnTimeRunsWholeWhereTheRoundHasNone) {
    constexpr int kAroundTheAim = kFirstStepsEveryFrame;
    SearchLimit all;
    all.ms = kAllTheTime;
    all.first_min_steps = kAroundTheAim;
    detect(round_from(0), &all);

    SearchLimit own;
    own.ms = kNoTime;
    own.first_ms = kAllTheTime;
    own.min_steps = 1;
    own.first_min_steps = kAroundTheAim;
    const Detection d = detect(round_from(0), &own);
    EXPECT_FALSE(d.found);
    EXPECT_EQ(own.first_held_steps_run, all.first_held_steps_run) << "every search of the whole frame";
    EXPECT_EQ(own.first_steps_into_next, 0) << "the first scan ran to its end";
    EXPECT_EQ(own.steps_run, 0) << "no time for the round";
}

// The round's half size first scan (part 0) where a large frame's first
// scan has searched the whole frame at half size already
// (SearchPlan::whole_frame_halved): its steps are counted, so that a held
// search's round keeps its place, and none is run again. At 640 x 480 the
// first scan stays at the frame's own size and part 0 runs.
TEST_F(SearchLimitOnAScreen, ALargeFramesRoundDoesNotSearchItsHalvedFirstScanAgain) {
    const std::vector<SearchPlan> with_part_0 = {spread_first(), search_piece(search_part(0), 0),
                                                 search_piece(search_part(0), 1)};
    for (const cv::Size resolution : {cv::Size(1280, 720), cv::Size(640, 480)}) {
        const bool large = resolution.width == 1280;
        SCOPED_TRACE(large ? "1280 x 720" : "640 x 480");
        photo_ = test::photograph_field(field_, 0, 10, 5, 20, 300, sim::ScreenKind::document, resolution);
        const Detection first_scan = detect({spread_first()});
        SearchLimit limit;
        limit.ms = kAllTheTime;
        const Detection d = detect(with_part_0, &limit);
        EXPECT_FALSE(d.found);
        EXPECT_EQ(limit.plans_done, 2) << "both pieces of part 0 taken";
        EXPECT_EQ(limit.steps_run, large ? 0 : 3) << "its three edgel sets' searches";
        if (large)
            EXPECT_EQ(d.grids_read, first_scan.grids_read);
        else
            EXPECT_GT(d.grids_read, first_scan.grids_read);
    }
}

}  // namespace
