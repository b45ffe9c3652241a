// Tests of pulsing opacity and hand-held camera trajectories.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/sim/sequence.hpp"

namespace {

using namespace umf::sim;

const cv::Size kSequenceScreen{1920, 1080};
constexpr int kFrames = 250;  // 10 s

TEST(SimSequence, PulseSwingsBetweenMinAndMax) {
    EXPECT_NEAR(pulse_opacity(0, 0.1, 0.3, 2), 0.1, 1e-12);
    EXPECT_NEAR(pulse_opacity(1, 0.1, 0.3, 2), 0.3, 1e-12);
    EXPECT_NEAR(pulse_opacity(0.5, 0.1, 0.3, 2), 0.2, 1e-12);
    EXPECT_NEAR(pulse_opacity(2, 0.1, 0.3, 2), 0.1, 1e-12);
}

TEST(SimSequence, TrajectoriesAreSeededAndSmooth) {
    for (Motion motion : kAllMotions) {
        const auto a = pose_trajectory(motion, kFrames, kSequenceScreen, 3);
        const auto b = pose_trajectory(motion, kFrames, kSequenceScreen, 3);
        const auto c = pose_trajectory(motion, kFrames, kSequenceScreen, 4);
        ASSERT_EQ(a.size(), std::size_t(kFrames));
        EXPECT_EQ(a.back().distance_mm, b.back().distance_mm) << to_string(motion);
        EXPECT_EQ(a.back().aim_screen_px, b.back().aim_screen_px) << to_string(motion);
        EXPECT_NE(a.back().roll_deg, c.back().roll_deg) << to_string(motion);
        for (std::size_t i = 1; i < a.size(); ++i) {
            EXPECT_LT(std::abs(a[i].distance_mm - a[i - 1].distance_mm), 20) << to_string(motion) << " frame " << i;
            EXPECT_LT(std::abs(a[i].pitch_deg - a[i - 1].pitch_deg), 5) << to_string(motion) << " frame " << i;
            EXPECT_LT(std::abs(a[i].yaw_deg - a[i - 1].yaw_deg), 5) << to_string(motion) << " frame " << i;
            EXPECT_LT(std::abs(a[i].roll_deg - a[i - 1].roll_deg), 8) << to_string(motion) << " frame " << i;
            EXPECT_LT(cv::norm(a[i].aim_screen_px - a[i - 1].aim_screen_px), 60) << to_string(motion) << " frame " << i;
        }
    }
}

template <typename F>
double span(const std::vector<umf::sim::CameraPose>& poses, F value) {
    const auto [lo, hi] = std::minmax_element(poses.begin(), poses.end(),
                                              [&](const auto& p, const auto& q) { return value(p) < value(q); });
    return value(*hi) - value(*lo);
}

TEST(SimSequence, CategoriesMoveWhatTheySay) {
    const auto tilt = [](const CameraPose& p) { return std::hypot(p.pitch_deg, p.yaw_deg); };
    const auto near_far = pose_trajectory(Motion::near_far, kFrames, kSequenceScreen, 1);
    EXPECT_GT(span(near_far, [](const CameraPose& p) { return p.distance_mm; }), 450);
    EXPECT_LT(span(near_far, tilt), 3);

    const auto horizontal = pose_trajectory(Motion::horizontal, kFrames, kSequenceScreen, 1);
    EXPECT_GT(span(horizontal, [](const CameraPose& p) { return p.aim_screen_px.x; }), 0.5 * kSequenceScreen.width);
    EXPECT_LT(span(horizontal, [](const CameraPose& p) { return p.aim_screen_px.y; }), 20);

    const auto rotation = pose_trajectory(Motion::rotation, kFrames, kSequenceScreen, 1);
    EXPECT_GT(span(rotation, [](const CameraPose& p) { return p.roll_deg; }), 300);

    const auto perspective = pose_trajectory(Motion::perspective, kFrames, kSequenceScreen, 1);
    const double max_tilt = tilt(*std::max_element(perspective.begin(), perspective.end(),
                                                   [&](const auto& p, const auto& q) { return tilt(p) < tilt(q); }));
    EXPECT_GT(max_tilt, 55);
    EXPECT_LT(max_tilt, 62);
}

}  // namespace
