#include "shared/detect/pulse_demodulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>
#include <random>
#include <string>

#include "shared/detect/detector.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"

using namespace umf;

namespace {

GreyView view_of(const std::vector<std::uint8_t>& pixels, int width, int height) {
    return {pixels.data(), width, height, width};
}

// 16 x 16 pixels of content at every grey level and a field of stripes
// three pixels wide, and a frame of them mixed at opacity `a`, rounded as a
// compositor rounds.
struct Busy {
    static constexpr int kSide = 16;
    std::vector<std::uint8_t> content, field;
    Busy() : content(kSide * kSide), field(kSide * kSide) {
        for (int i = 0; i < kSide * kSide; ++i) {
            content[i] = static_cast<std::uint8_t>((i * 37) % 256);
            field[i] = (i / 3) % 2 ? 255 : 0;
        }
    }
    const std::vector<std::uint8_t>& mixed(double a) {
        frame.resize(content.size());
        for (std::size_t i = 0; i < frame.size(); ++i)
            frame[i] = static_cast<std::uint8_t>(std::lround((1 - a) * content[i] + a * field[i]));
        return frame;
    }
    std::vector<std::uint8_t> frame;
};

TEST(PulseDemodulator, TheSlopeOfEachPixelIsTheFieldLessTheContent) {
    // Content and field of every combination, mixed as a compositor does.
    Busy busy;
    const auto& content = busy.content;
    const auto& field = busy.field;
    const int width = Busy::kSide, height = Busy::kSide;
    PulseDemodulator demodulator;
    EXPECT_EQ(demodulator.field_image().data, nullptr) << "no frames";
    for (const double a : {0.01, 0.02, 0.03, 0.04, 0.03, 0.02}) {
        demodulator.add(view_of(busy.mixed(a), width, height), a);
        if (a == 0.01) {
            EXPECT_EQ(demodulator.field_image().data, nullptr) << "one opacity has no slope";
        }
    }
    EXPECT_DOUBLE_EQ(demodulator.weight(), 6);
    EXPECT_NEAR(demodulator.opacity_spread(), 0.01, 0.001);
    const GreyView out = demodulator.field_image();
    ASSERT_NE(out.data, nullptr);
    ASSERT_EQ(out.width, width);
    ASSERT_EQ(out.height, height);
    // Each frame rounds to whole grey levels: half a level over an opacity
    // spread of 0.01 is tens of levels of slope. The sign is what counts:
    // the field's light modules light, its dark ones dark, wherever the
    // content is not at the module's own colour.
    int right = 0, compared = 0;
    for (int i = 0; i < width * height; ++i) {
        const double slope = static_cast<double>(field[i]) - content[i];
        if (std::abs(slope) < 64) continue;
        ++compared;
        right += (out.data[i] > 128) == (slope > 0);
    }
    EXPECT_GT(compared, 100);
    EXPECT_EQ(right, compared);
}

TEST(PulseDemodulator, ExactFramesGiveTheExactSlope) {
    // Frames without rounding: grey levels that are whole at every opacity.
    const int width = 4, height = 1;
    PulseDemodulator demodulator;
    // I = C + a (F - C) with F - C = -200, -100, 100, 200 and C = 200, 100, 0, 0: whole at a = k / 100.
    const int c[] = {200, 100, 0, 0}, d[] = {-200, -100, 100, 200};
    for (const int k : {0, 50, 100}) {
        std::vector<std::uint8_t> frame(width);
        for (int x = 0; x < width; ++x) frame[x] = static_cast<std::uint8_t>(c[x] + d[x] * k / 100);
        demodulator.add(view_of(frame, width, height), k / 100.0);
    }
    const GreyView out = demodulator.field_image();
    ASSERT_NE(out.data, nullptr);
    for (int x = 0; x < width; ++x) EXPECT_NEAR(out.data[x], 127.5 + d[x] / 2.0, 0.5) << x;
}

TEST(PulseDemodulator, FollowedOutToFullOpacityTheContentIsGone) {
    // Exact frames: the values given are 0, 1/2 and 1, the opacities 0.2,
    // 0.4 and 0.6. I = C + a (F - C) is whole at each of them.
    const int c[] = {200, 0, 100, 50}, f[] = {0, 255, 255, 0};
    const int width = 4;
    PulseDemodulator demodulator;
    EXPECT_EQ(demodulator.full_opacity_image(0.2, 0.6).data, nullptr) << "no frames";
    for (const int k : {0, 1, 2}) {
        const double a = 0.2 + 0.2 * k;
        std::vector<std::uint8_t> frame(width);
        for (int x = 0; x < width; ++x) frame[x] = static_cast<std::uint8_t>(std::lround(c[x] + a * (f[x] - c[x])));
        demodulator.add(view_of(frame, width, 1), k / 2.0);
    }
    const GreyView alone = demodulator.full_opacity_image(0.2, 0.6);
    ASSERT_NE(alone.data, nullptr);
    for (int x = 0; x < width; ++x) EXPECT_NEAR(alone.data[x], f[x], 0.5) << x;
    // The other sign (the course read backwards) is not the field.
    const GreyView backwards = demodulator.full_opacity_image(0.6, 0.2);
    EXPECT_NEAR(backwards.data[0], 240, 0.5) << "160 - (80 - 160)";
    EXPECT_EQ(demodulator.full_opacity_image(0.3, 0.3).data, nullptr) << "no range";
}

TEST(PulseDemodulator, TheFieldAloneIsRightWhereTheContentIsAtTheModulesColour) {
    // A busy content under a faint pulse (0.01 to 0.04), each frame rounded
    // to whole levels: the slope is the field less the content, and where
    // the content is at a module's own colour it holds no field; the frames
    // followed out to opacity 1 hold it on every pixel.
    Busy busy;
    const auto& field = busy.field;
    const int width = Busy::kSide, height = Busy::kSide;
    PulseDemodulator demodulator;
    for (int k = 0; k < 36; ++k) {
        const double u = 0.5 - 0.5 * std::cos(2 * M_PI * k / 36.0);
        demodulator.add(view_of(busy.mixed(0.01 + 0.03 * u), width, height), u);
    }
    const GreyView alone = demodulator.full_opacity_image(0.01, 0.04);
    ASSERT_NE(alone.data, nullptr);
    int right = 0;
    double error = 0;
    for (int i = 0; i < width * height; ++i) {
        right += (alone.data[i] > 128) == (field[i] > 128);
        error += std::abs(alone.data[i] - field[i]) / static_cast<double>(width * height);
    }
    EXPECT_EQ(right, width * height);
    EXPECT_LT(error, 20);
}

TEST(PulseDemodulator, ForgetsOldFramesAndStartsOverAtAnotherSize) {
    PulseDemodulator demodulator(0.5);
    std::vector<std::uint8_t> small(4, 10), big(16, 10);
    for (int i = 0; i < 20; ++i) demodulator.add(view_of(small, 2, 2), i % 2 ? 0.1 : 0.2);
    EXPECT_NEAR(demodulator.weight(), 2, 1e-3) << "1 + 1/2 + 1/4 + ...";
    demodulator.add(view_of(big, 4, 4), 0.1);
    EXPECT_DOUBLE_EQ(demodulator.weight(), 1);
    EXPECT_EQ(demodulator.field_image().data, nullptr);
    demodulator.add(view_of(big, 4, 4), 0.3);
    EXPECT_EQ(demodulator.field_image().width, 4);
    EXPECT_THROW(demodulator.add(view_of(big, 4, 4), 1.5), std::invalid_argument);
    EXPECT_THROW(demodulator.add(GreyView{}, 0.1), std::invalid_argument);
}

// Small frames of a page of soft-edged blocks (8 px, blurred twice over 7
// px, as a camera's frame is soft), wider than the view, shot `left` pixels
// along it.
class SlidingPage {
public:
    static constexpr int kWidth = 160, kHeight = 120, kPageWidth = 400;
    SlidingPage() : page_(kPageWidth * kHeight), frame_(kWidth * kHeight) {
        std::mt19937 rng(11);
        std::uniform_int_distribution<int> grey(30, 225);
        std::vector<int> blocks((kPageWidth / 8 + 1) * (kHeight / 8 + 1));
        for (int& b : blocks) b = grey(rng);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kPageWidth; ++x) page_[y * kPageWidth + x] = blocks[(y / 8) * (kPageWidth / 8 + 1) + x / 8];
        for (const bool across : {true, false}) {
            std::vector<double> blurred(page_.size());
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kPageWidth; ++x) {
                    double sum = 0;
                    int n = 0;
                    for (int d = -3; d <= 3; ++d) {
                        const int u = across ? x + d : x, v = across ? y : y + d;
                        if (u < 0 || v < 0 || u >= kPageWidth || v >= kHeight) continue;
                        sum += page_[v * kPageWidth + u];
                        ++n;
                    }
                    blurred[y * kPageWidth + x] = sum / n;
                }
            page_ = std::move(blurred);
        }
    }
    GreyView shoot(int left) {
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                frame_[y * kWidth + x] = static_cast<std::uint8_t>(std::lround(page_[y * kPageWidth + x + left]));
        return view_of(frame_, kWidth, kHeight);
    }

private:
    std::vector<double> page_;
    std::vector<std::uint8_t> frame_;
};

// The registration's motion check (PulseSearchOptions::max_motion_change) on
// small frames of a textured page: a hand's swing that speeds up by a little
// each frame stays registered, and so does one that speeds up by more than
// the check allows from the last motion, its change carried on. A view held
// still that jumps by 11 pixels in one frame stays registered where the
// frames show it (the alignment leaves far less unexplained than the motion
// guessed, and comes to the same place from where the view stood); with the
// motion check alone (on a blank page, a registration a few modules off
// explains hardly more than the guess), it is refused.
TEST(PulseSearch, ASwingStaysRegisteredAndAJumpWhereTheFramesShowIt) {
    SlidingPage page;
    auto shoot = [&](int left) { return page.shoot(left); };
    // Steps of 4, 5, 7 and 10 pixels: each changes by at most 3 pixels, less
    // than 3 % of the width (4.8).
    PulseSearch swing{PulseSearchOptions{}};
    for (const int left : {0, 4, 9, 16, 26}) swing.add(shoot(left));
    EXPECT_EQ(swing.registration_losses(), 0);
    ASSERT_TRUE(swing.motion().has_value());
    EXPECT_NEAR((*swing.motion())(0, 2), -10, 0.1) << *swing.motion();
    // Steps of 4, 8, 13, 19 and 26 pixels: changes of 5 to 7 pixels from
    // the last step, of 1 from the last change carried on.
    PulseSearch faster{PulseSearchOptions{}};
    for (const int left : {0, 4, 12, 25, 44, 70}) faster.add(shoot(left));
    EXPECT_EQ(faster.registration_losses(), 0);
    ASSERT_TRUE(faster.motion().has_value());
    EXPECT_NEAR((*faster.motion())(0, 2), -26, 0.1) << *faster.motion();

    PulseSearch still{PulseSearchOptions{}};
    for (int i = 0; i < 4; ++i) still.add(shoot(100 + i % 2));
    EXPECT_EQ(still.registration_losses(), 0);
    still.add(shoot(112));
    EXPECT_EQ(still.registration_losses(), 0) << "a jump of 11 pixels that the frames show";
    ASSERT_TRUE(still.motion().has_value());
    EXPECT_NEAR((*still.motion())(0, 2), -11, 0.1) << *still.motion();
    const FrameRegistration& jump = still.last_registration();
    EXPECT_LE(jump.residual, PulseSearchOptions{}.out_of_step_share * jump.guess_residual);

    // Without that, the motion check has the last word.
    PulseSearchOptions checked_only;
    checked_only.out_of_step_share = 0;
    PulseSearch refused{checked_only};
    for (int i = 0; i < 4; ++i) refused.add(shoot(100 + i % 2));
    refused.add(shoot(112));
    EXPECT_EQ(refused.registration_losses(), 1) << "a jump of 11 pixels after a still view, checked alone";
}

// A frame that cannot be laid onto the last is set aside, and the next is
// laid onto the frames kept across it: they are kept and the motion goes
// on. A place carried comes through where the frame set aside was refused
// with its alignment in step with the hand (a frame smeared flat), not
// where it was aligned far off. Two such frames in a row are a cut: the
// frames kept start over from the first of them.
TEST(PulseSearch, StepsAcrossAFrameThatCannotBeRegistered) {
    SlidingPage page;
    const Eigen::Vector2d aim(80, 60);
    // A place at the aim: field units of a tenth of a pixel.
    Detection place;
    place.found = true;
    place.aim_image = aim;
    place.aim_field = {50, 30};
    place.image_to_field << 0.1, 0, 42, 0, 0.1, 24, 0, 0, 1;

    // A hand moving the view a pixel a frame.
    PulseSearch search{PulseSearchOptions{}};
    for (const int left : {0, 1, 2, 3}) search.add(page.shoot(left));
    search.found_elsewhere(place);
    search.add(page.shoot(4));
    ASSERT_TRUE(search.carried(aim).has_value());
    // The next frame in its place, smeared by the hand across 15 pixels:
    // aligned in step with the hand, and refused for all it leaves
    // unexplained.
    const GreyView next = page.shoot(5);
    std::vector<std::uint8_t> smeared(next.data, next.data + SlidingPage::kWidth * SlidingPage::kHeight);
    for (int y = 0; y < SlidingPage::kHeight; ++y)
        for (int x = 0; x < SlidingPage::kWidth; ++x) {
            int sum = 0, n = 0;
            for (int u = std::max(0, x - 7); u <= std::min(SlidingPage::kWidth - 1, x + 7); ++u, ++n)
                sum += next.at(u, y);
            smeared[y * SlidingPage::kWidth + x] = static_cast<std::uint8_t>((sum + n / 2) / n);
        }
    search.add(view_of(smeared, SlidingPage::kWidth, SlidingPage::kHeight));
    EXPECT_EQ(search.registration_losses(), 1);
    EXPECT_EQ(search.frames(), 1) << "the newest lies among no frames kept";
    EXPECT_FALSE(search.motion().has_value());
    EXPECT_FALSE(search.carried(aim).has_value()) << "not said of a frame set aside";
    search.add(page.shoot(6));
    EXPECT_EQ(search.registration_losses(), 1);
    EXPECT_EQ(search.frames(), 6) << "laid across the frame set aside onto the five kept";
    EXPECT_EQ(search.last_registration_span(), 2);
    ASSERT_TRUE(search.motion().has_value());
    EXPECT_NEAR((*search.motion())(0, 2), -1, 0.1) << "one frame's motion, as before";
    const std::optional<Detection> across = search.carried(aim);
    ASSERT_TRUE(across.has_value()) << "carried across the frame set aside";
    EXPECT_NEAR(across->aim_field.x(), 50 + 0.3, 0.02) << "the view came 3 px along since the place was found";
    EXPECT_NEAR(across->aim_field.y(), 30, 0.02);
    ASSERT_TRUE(search.carry(aim).has_value());
    EXPECT_EQ(search.carry(aim)->frames, 3) << "the frame set aside counts";

    // A frame of another part of the page (a registration far off): the
    // frames kept go on across it, the place is not carried.
    search.add(page.shoot(200));
    search.add(page.shoot(8));
    EXPECT_EQ(search.registration_losses(), 2);
    EXPECT_EQ(search.frames(), 7);
    EXPECT_FALSE(search.carried(aim).has_value()) << "not carried across a frame out of step with the hand";

    // A cut to another part of the page, held: the first frame after it is
    // set aside, the second starts the frames kept over from it.
    search.found_elsewhere(place);
    search.add(page.shoot(200));
    search.add(page.shoot(201));
    EXPECT_EQ(search.registration_losses(), 3);
    EXPECT_EQ(search.frames(), 2);
    EXPECT_FALSE(search.carried(aim).has_value()) << "not carried across a cut";
    ASSERT_TRUE(search.motion().has_value());
    EXPECT_NEAR((*search.motion())(0, 2), -1, 0.1);
}

// PulseSearch's every step on small frames of a checkerboard pulsing over
// noise: registered at rest, a pulse, its shape fitted, both signs demodulated, and the
// detector, which finds no field in a checkerboard, has the last word.
TEST(PulseSearch, RunsEveryStepOnAPulseThatIsNoField) {
    const Detector detector(load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json"));
    const int width = 160, height = 120;
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> grey(40, 215);
    std::normal_distribution<double> noise(0, 1.5);
    std::vector<std::uint8_t> content(width * height);
    for (auto& c : content) c = static_cast<std::uint8_t>(grey(rng));
    const overlay::Preset pulse = [] {
        overlay::Preset p;
        p.opacity_min = 0.01;
        p.opacity_max = 0.04;
        p.period_s = 1.5;
        return p;
    }();
    overlay::Preset unit = pulse;
    unit.opacity_min = 0;
    unit.opacity_max = 1;
    unit.period_s = 1;
    PulseSearchOptions options;
    options.shape = PulseShape{[unit](double phase) { return overlay::opacity_at(unit, phase); }, 1.5};
    options.frame_rates = {25};
    PulseSearch search(options);
    std::vector<std::uint8_t> frame(width * height);
    for (int i = 0; i < 20; ++i) {
        const double a = overlay::opacity_at(pulse, 0.3 + i / 25.0);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const double f = ((x / 10 + y / 10) % 2) ? 255 : 0;
                const double v = (1 - a) * content[y * width + x] + a * f + noise(rng);
                frame[y * width + x] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
            }
        search.add(view_of(frame, width, height));
    }
    ASSERT_TRUE(search.due());
    const PulseSearchResult r = search.search(detector, {80, 60});
    EXPECT_FALSE(r.detection.found);
    EXPECT_EQ(r.frames, 20);
    EXPECT_GT(r.share, 0.2);
    EXPECT_TRUE(r.fitted);
    EXPECT_EQ(search.registration_losses(), 0) << "the frames of a view at rest are registered";
    ASSERT_TRUE(search.motion().has_value());
    for (const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(width - 1, height - 1, 1)}) {
        const Eigen::Vector3d moved = *search.motion() * corner;
        EXPECT_LT((moved.head<2>() / moved.z() - corner.head<2>()).norm(), 0.2) << *search.motion();
    }
    for (const char* pulse_search_reason : {"too few frames for the pulse", "no pulse in the frames"})
        EXPECT_NE(r.detection.failure, pulse_search_reason);
    EXPECT_FALSE(r.detection.failure.empty());
}

}  // namespace
