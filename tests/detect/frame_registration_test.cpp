#include "shared/detect/frame_registration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace umf {
namespace {

// A screen-like picture: text-sized dark blocks on a light page, a few
// large shapes and a soft shading, so there are edges at every scale.
std::vector<std::uint8_t> page_picture(int w, int h, std::uint32_t seed) {
    std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    std::uint32_t state = seed;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return state >> 8;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            px[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint8_t>(200 + 30 * std::sin(x * 0.01 + y * 0.013));
    const auto block = [&](int x0, int y0, int bw, int bh, int grey) {
        for (int y = std::max(0, y0); y < std::min(h, y0 + bh); ++y)
            for (int x = std::max(0, x0); x < std::min(w, x0 + bw); ++x)
                px[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint8_t>(grey);
    };
    for (int i = 0; i < 6; ++i)
        block(static_cast<int>(next() % w), static_cast<int>(next() % h), 40 + static_cast<int>(next() % 120),
              30 + static_cast<int>(next() % 90), 60 + static_cast<int>(next() % 100));
    for (int line = 20; line < h - 20; line += 18)
        for (int x = 16; x < w - 40;) {
            const int word = 8 + static_cast<int>(next() % 40);
            block(x, line, word, 9, 30 + static_cast<int>(next() % 50));
            x += word + 6;
        }
    // As a camera's lens sees it: no edge sharper than a pixel or two.
    std::vector<std::uint8_t> soft;
    const GreyView blurred = smoothed(GreyView{px.data(), w, h, w}, soft);
    std::copy_n(blurred.data, px.size(), px.data());
    return px;
}

GreyView view_of(const std::vector<std::uint8_t>& px, int w, int h) { return {px.data(), w, h, w}; }

// How far apart two homographies take the frame's corners and centre.
double farthest_apart(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, int w, int h) {
    double most = 0;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(w - 1, 0, 1), Eigen::Vector3d(0, h - 1, 1),
                                    Eigen::Vector3d(w - 1, h - 1, 1), Eigen::Vector3d(w / 2.0, h / 2.0, 1)}) {
        const Eigen::Vector3d qa = a * p, qb = b * p;
        most = std::max(most, (qa.head<2>() / qa.z() - qb.head<2>() / qb.z()).norm());
    }
    return most;
}

// A hand-held phone's motion between frames 25 a second apart, and more:
// a shift, a turn about the view's centre, a nod of perspective.
Eigen::Matrix3d motion(double dx, double dy, double degrees, double scale, double tilt, int w, int h) {
    const double a = degrees * 3.14159265358979 / 180;
    Eigen::Matrix3d centre = Eigen::Matrix3d::Identity(), back = Eigen::Matrix3d::Identity();
    centre(0, 2) = -w / 2.0;
    centre(1, 2) = -h / 2.0;
    back(0, 2) = w / 2.0 + dx;
    back(1, 2) = h / 2.0 + dy;
    Eigen::Matrix3d turn;
    turn << scale * std::cos(a), -scale * std::sin(a), 0, scale * std::sin(a), scale * std::cos(a), 0, tilt, 0, 1;
    return back * turn * centre;
}

TEST(FrameRegistration, FindsTheMotionBetweenTwoFramesOfAPage) {
    const int w = 640, h = 480;
    const auto page = page_picture(w, h, 7);
    const GreyView from = view_of(page, w, h);
    const FramePyramid from_levels(from);
    EXPECT_EQ(from_levels.levels(), 4);  // 640, 320, 160, 80
    for (const Eigen::Matrix3d& truth : {motion(6, -4, 1.5, 1.0, 0, w, h), motion(-12, 9, -3, 1.03, 0, w, h),
                                        motion(3, 2, 0.5, 0.98, 4e-5, w, h), motion(25, 0, 0, 1, 0, w, h)}) {
        std::vector<std::uint8_t> moved;
        const GreyView to = warp_frame(from, truth, from, moved);
        // The pulse and the exposure change the grey levels too.
        for (std::uint8_t& p : moved) p = static_cast<std::uint8_t>(std::min(255, p + 6));
        const FrameRegistration r = register_frames(from_levels, FramePyramid(to));
        ASSERT_TRUE(r.registered) << "residual " << r.residual << ", overlap " << r.overlap;
        EXPECT_LT(farthest_apart(r.homography, truth, w, h), 0.3) << r.homography;
        EXPECT_LT(r.residual, 6);
    }
}

// A phone's auto-exposure darkens the next frame by 15 %: the page's light
// grey drops by 30 levels, the text's dark one by 5, a spread an offset
// alone leaves as residual and a gain takes out.
TEST(FrameRegistration, FitsTheExposuresGain) {
    const int w = 640, h = 480;
    const auto page = page_picture(w, h, 5);
    const GreyView from = view_of(page, w, h);
    const Eigen::Matrix3d truth = motion(-5, 7, 1, 1.01, 0, w, h);
    std::vector<std::uint8_t> moved;
    const GreyView to = warp_frame(from, truth, from, moved);
    for (std::uint8_t& p : moved) p = static_cast<std::uint8_t>(std::lround(0.85 * p));
    RegistrationOptions with_gain;
    with_gain.fit_gain = true;
    const FrameRegistration r = register_frames(FramePyramid(from), FramePyramid(to), Eigen::Matrix3d::Identity(), with_gain);
    ASSERT_TRUE(r.registered) << "residual " << r.residual << ", overlap " << r.overlap;
    EXPECT_NEAR(r.gain, 0.85, 0.02);
    EXPECT_LT(farthest_apart(r.homography, truth, w, h), 0.3) << r.homography;
    EXPECT_LT(r.residual, 4);
    const FrameRegistration o = register_frames(FramePyramid(from), FramePyramid(to));
    EXPECT_DOUBLE_EQ(o.gain, 1);
    EXPECT_GT(o.residual, 1.5 * r.residual) << "an offset alone leaves the exposure's change";
}

TEST(FrameRegistration, StartsFromTheGuessForALargerMotion) {
    const int w = 640, h = 480;
    const auto page = page_picture(w, h, 11);
    const GreyView from = view_of(page, w, h);
    const Eigen::Matrix3d truth = motion(70, -50, 6, 1.06, 0, w, h);
    std::vector<std::uint8_t> moved;
    const GreyView to = warp_frame(from, truth, from, moved);
    const FrameRegistration guessed =
        register_frames(FramePyramid(from), FramePyramid(to), motion(60, -45, 5, 1.05, 0, w, h));
    ASSERT_TRUE(guessed.registered);
    EXPECT_LT(farthest_apart(guessed.homography, truth, w, h), 0.3);
    // Where the guess laid the frames, a few pixels off, the spread is far
    // more than aligned, and less than unmoved.
    EXPECT_GT(guessed.guess_residual, 2 * guessed.residual);
    EXPECT_LT(guessed.guess_residual, guessed.unmoved_residual);
    const FrameRegistration unguessed = register_frames(FramePyramid(from), FramePyramid(to));
    EXPECT_EQ(unguessed.guess_residual, unguessed.unmoved_residual) << "from where the view stands";
}

TEST(FrameRegistration, SaysWhenTheFramesShowDifferentScenes) {
    const int w = 320, h = 240;
    const auto one = page_picture(w, h, 1), other = page_picture(w, h, 2);
    const FrameRegistration r = register_frames(FramePyramid(view_of(one, w, h)), FramePyramid(view_of(other, w, h)));
    EXPECT_FALSE(r.registered) << "residual " << r.residual << " of " << r.unmoved_residual;
    EXPECT_GT(r.residual, RegistrationOptions{}.max_residual);
    EXPECT_GT(r.residual, RegistrationOptions{}.max_share * r.unmoved_residual);
}

TEST(FrameRegistration, RefusesFramesOfDifferentSizes) {
    const auto big = page_picture(320, 240, 1), small = page_picture(160, 120, 1);
    EXPECT_THROW(register_frames(FramePyramid(view_of(big, 320, 240)), FramePyramid(view_of(small, 160, 120))),
                 std::invalid_argument);
    std::vector<std::uint8_t> out;
    EXPECT_THROW(warp_frame(view_of(big, 320, 240), Eigen::Matrix3d::Identity(), view_of(small, 160, 120), out),
                 std::invalid_argument);
}

TEST(FrameRegistration, WarpKeepsTheOtherFramesPixelsWhereNothingMapsFromTheFrame) {
    const int w = 64, h = 48;
    const std::vector<std::uint8_t> dark(static_cast<std::size_t>(w * h), 10), light(static_cast<std::size_t>(w * h), 240);
    Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
    shift(0, 2) = 20;  // the frame's points move 20 px to the right
    std::vector<std::uint8_t> out;
    const GreyView warped = warp_frame(view_of(dark, w, h), shift, view_of(light, w, h), out);
    EXPECT_EQ(warped.at(5, 10), 240);   // nothing of the frame lands there
    EXPECT_EQ(warped.at(40, 10), 10);   // the frame's pixel from x = 20
    EXPECT_EQ(warped.at(19, 10), 240);
    EXPECT_EQ(warped.at(20, 10), 10);
}

// A ramp's pyramid: each level's pixel holds the ramp's value where the
// level map puts its centre in the frame, half a pixel or more off with the
// centres taken for the same.
TEST(FrameRegistration, LevelMapPutsALevelsPixelsWhereThePyramidTookThem) {
    const int w = 64, h = 48;
    std::vector<std::uint8_t> ramp(static_cast<std::size_t>(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) ramp[static_cast<std::size_t>(y * w + x)] = static_cast<std::uint8_t>(2 * x + y);
    const FramePyramid pyramid(view_of(ramp, w, h), 16);
    ASSERT_EQ(pyramid.levels(), 3);
    for (int level = 1; level < 3; ++level) {
        const LevelMap map(level);
        const GreyView v = pyramid.level(level);
        for (int y = 1; y + 1 < v.height; ++y)
            for (int x = 1; x + 1 < v.width; ++x) {
                const Eigen::Vector2d at = map.to_frame(Eigen::Vector2d(x, y));
                // Each level's means rounded: half a level more each level down.
                EXPECT_NEAR(v.at(x, y), 2 * at.x() + at.y(), 0.5 * level) << "level " << level << " at " << x << ", " << y;
                EXPECT_LT((map.from_frame(at) - Eigen::Vector2d(x, y)).norm(), 1e-12);
            }
    }
    // A motion between frames, at a level: 6 px along x is 3 at half size.
    Eigen::Matrix3d motion = Eigen::Matrix3d::Identity();
    motion(0, 0) = 1.1;
    motion(0, 2) = 6;
    const LevelMap half(1);
    const Eigen::Vector2d p(20, 30);
    const Eigen::Vector3d q = half.homography(motion) * half.from_frame(p).homogeneous();
    const Eigen::Vector3d r = motion * p.homogeneous();
    EXPECT_LT((q.hnormalized() - half.from_frame(r.hnormalized())).norm(), 1e-12);
}

}  // namespace
}  // namespace umf
