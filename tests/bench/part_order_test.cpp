// The order of the search's parts is chosen with part_order.hpp: a frame
// waits for the parts before the one that finds it, and the greedy order
// puts first what finds the most frames for the time it adds to all of them.
#include "tests/bench/part_order.hpp"

#include <gtest/gtest.h>

namespace {

using umf::bench::greedy_order;
using umf::bench::mean_time_to_find;
using umf::bench::PartFinds;

// Every part costing `ms`, but those named.
PartFinds costing(double ms, std::map<int, double> named, std::vector<unsigned> found_by) {
    PartFinds set{std::move(found_by), {}};
    for (int k = 0; k < umf::kSearchParts; ++k) set.cost[k] = named.count(k) ? named[k] : ms;
    return set;
}

TEST(PartOrder, AFrameWaitsForThePartsBeforeTheOneThatFindsIt) {
    // Frame a: only part 1 finds it; frame b: parts 0 and 1; frame c: none.
    const PartFinds set = costing(5, {{0, 1}, {1, 10}}, {0b10u, 0b11u, 0u});
    std::vector<int> order{0, 1};
    for (int k = 2; k < umf::kSearchParts; ++k) order.push_back(k);
    // a: 1 + 10; b: 1; c: every part, 1 + 10 + 10 x 5.
    EXPECT_DOUBLE_EQ(mean_time_to_find(order, {set}), (11.0 + 1.0 + 61.0) / 3);
    std::swap(order[0], order[1]);
    EXPECT_DOUBLE_EQ(mean_time_to_find(order, {set}), (10.0 + 10.0 + 61.0) / 3);
}

TEST(PartOrder, GreedyPutsFirstWhatFindsMostForItsCostOverEveryResolution) {
    // At one resolution part 3 finds two of three frames for 2 ms, part 5
    // all three for 20 ms; at the other, part 7 is not run (0 ms) and finds
    // the one frame there.
    const PartFinds vga = costing(30, {{3, 2}, {5, 20}, {7, 0}}, {1u << 3 | 1u << 5, 1u << 3 | 1u << 5, 1u << 5});
    const PartFinds hd = costing(30, {{3, 4}, {5, 40}}, {1u << 7});
    const std::vector<int> order = greedy_order({vga, hd});
    ASSERT_EQ(order.size(), static_cast<std::size_t>(umf::kSearchParts));
    // First part 3 (two frames for 3 x 2 + 4 ms), then part 7 (the other
    // resolution's frame, for nothing at the first and 30 ms at the other),
    // then part 5 (the last frame, for 20 ms).
    EXPECT_EQ(order[0], 3);
    EXPECT_EQ(order[1], 7);
    EXPECT_EQ(order[2], 5);
    EXPECT_LT(mean_time_to_find(order, {vga, hd}), mean_time_to_find({5, 7, 3, 0, 1, 2, 4, 6, 8, 9, 10, 11}, {vga, hd}));
}

}  // namespace
