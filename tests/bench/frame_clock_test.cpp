// The real-time clock of umf_benchmark --realtime: which frames a slower
// device's tracker is free for.
#include <gtest/gtest.h>

#include "tests/bench/frame_clock.hpp"

namespace {

using umf::bench::FrameClock;

TEST(FrameClock, OfflineEveryFrameIsLookedAt) {
    FrameClock clock(0, 25);
    clock.took(0, 500);
    EXPECT_TRUE(clock.free_for(1));
}

TEST(FrameClock, ASlowFrameCostsTheFramesThatArriveMeanwhile) {
    FrameClock clock(4, 25);  // a frame every 40 ms
    ASSERT_TRUE(clock.free_for(0));
    clock.took(0, 30);  // 120 ms on the device
    EXPECT_FALSE(clock.free_for(1));
    EXPECT_FALSE(clock.free_for(2));
    EXPECT_TRUE(clock.free_for(3));  // arrives at 120 ms, as the tracker finishes
    clock.took(3, 2);                // 8 ms: done before the next frame
    EXPECT_TRUE(clock.free_for(4));
}

}  // namespace
