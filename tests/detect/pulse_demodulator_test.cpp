#include "shared/detect/pulse_demodulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/pulse_course.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

GreyView view_of(const std::vector<std::uint8_t>& pixels, int width, int height) {
    return {pixels.data(), width, height, width};
}

TEST(PulseDemodulator, TheSlopeOfEachPixelIsTheFieldLessTheContent) {
    // Content and field of every combination, mixed as a compositor does.
    const int width = 16, height = 16;
    std::vector<std::uint8_t> content(width * height), field(width * height);
    for (int i = 0; i < width * height; ++i) {
        content[i] = static_cast<std::uint8_t>((i * 37) % 256);
        field[i] = (i / 3) % 2 ? 255 : 0;
    }
    PulseDemodulator demodulator;
    EXPECT_EQ(demodulator.field_image().data, nullptr) << "no frames";
    std::vector<std::uint8_t> frame(width * height);
    for (const double a : {0.01, 0.02, 0.03, 0.04, 0.03, 0.02}) {
        for (int i = 0; i < width * height; ++i)
            frame[i] = static_cast<std::uint8_t>(std::lround((1 - a) * content[i] + a * field[i]));
        demodulator.add(view_of(frame, width, height), a);
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

struct PulseCase {
    const char* name;
    sim::ScreenKind screen;
};

class PulseDemodulatorOnBusyScreens : public ::testing::TestWithParam<PulseCase> {};

// A phone held still before a busy screen whose field pulses between
// opacity 0.01 and 0.04 (sine, 1.5 s) at 25 frames a second: over the 19
// frames of the pulse's rise the demodulated image holds the field, and the
// detector finds it there within a twentieth of a module. (The top frame
// alone, at 0.04, is found on the document and the dark code, not on the
// web page or the photo; the demodulated image finds all four down to a
// pulse between 0.002 and 0.01.)
TEST_P(PulseDemodulatorOnBusyScreens, FindsTheFieldOfAFaintPulse) {
    const PulseCase c = GetParam();
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    const overlay::Preset pulse = test::sine_pulse(0.01, 0.04, 1.5);
    test::Photo p;
    p.camera.resolution = {640, 480};
    p.pose.distance_mm = 300;
    p.pose.pitch_deg = 12;
    p.pose.yaw_deg = -8;
    p.pose.roll_deg = 15;
    p.pose.aim_screen_px = {950, 520};
    const std::vector<cv::Mat> shots = test::film_pulse(f, p, c.screen, pulse, 19);
    PulseDemodulator demodulator;
    std::vector<double> opacities;
    for (std::size_t i = 0; i < shots.size(); ++i) {
        opacities.push_back(overlay::opacity_at(pulse, static_cast<double>(i) / 25.0));
        demodulator.add({shots[i].data, shots[i].cols, shots[i].rows, static_cast<std::ptrdiff_t>(shots[i].step)},
                        opacities.back());
    }
    const GreyView field = demodulator.field_image();
    ASSERT_NE(field.data, nullptr);
    const Detection d = detector.detect(field);
    ASSERT_TRUE(d.found) << c.name << ": " << d.failure;
    const cv::Point2d truth = sim::image_to_field(p.shot, p.placement, {320, 240});
    EXPECT_LT(std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y), 0.05)
        << c.name << ": found (" << d.aim_field.x() << ", " << d.aim_field.y() << "), truth (" << truth.x << ", "
        << truth.y << ")";

    // The pulse's course from the frames alone: the opacities up to a
    // factor and a sign; of the two signs, the field is found in one.
    std::vector<GreyView> views;
    for (const cv::Mat& m : shots) views.push_back({m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)});
    const PulseCourse course = find_pulse_course(views);
    ASSERT_EQ(course.level.size(), views.size());
    EXPECT_GT(course.share, 0.3) << c.name;
    double along = 0, mean = 0;
    for (double a : opacities) mean += a / static_cast<double>(opacities.size());
    for (std::size_t i = 0; i < views.size(); ++i) along += course.level[i] * (opacities[i] - mean);
    int found = 0;
    for (const double sign : {1.0, -1.0}) {
        PulseDemodulator blind;
        for (std::size_t i = 0; i < views.size(); ++i) blind.add(views[i], 0.5 + 0.5 * sign * course.level[i]);
        const Detection e = detector.detect(blind.field_image(PulseDemodulator::SlopeScale::spread));
        if (!e.found) continue;
        ++found;
        EXPECT_GT(sign * along, 0) << c.name << ": found with the course inverted";
        EXPECT_LT(std::hypot(e.aim_field.x() - truth.x, e.aim_field.y() - truth.y), 0.05) << c.name;
    }
    EXPECT_EQ(found, 1) << c.name;
}

TEST(PulseCourse, NoiseAloneExplainsLittle) {
    // A screen at rest under a steady field: the frames differ by their noise.
    const Field f = test::shipped_field("b4-64x36.json");
    std::vector<cv::Mat> shots;
    std::vector<GreyView> views;
    const test::Photo p = test::photograph_field(f, 0.3, 10, 5, 20, 300, sim::ScreenKind::web_page);
    for (int frame = 0; frame < 12; ++frame) {
        cv::Mat noisy = p.shot.grey.clone();
        cv::Mat noise(noisy.size(), CV_16S);
        cv::randn(noise, 0, 2);
        noisy.convertTo(noisy, CV_16S);
        noisy += noise;
        noisy.convertTo(noisy, CV_8U);
        shots.push_back(noisy);
    }
    for (const cv::Mat& m : shots) views.push_back({m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)});
    const PulseCourse course = find_pulse_course(views);
    ASSERT_EQ(course.level.size(), 12u);
    EXPECT_LT(course.share, 0.2);
    EXPECT_TRUE(find_pulse_course(std::span<const GreyView>(views.data(), 2)).level.empty()) << "two frames";
}

INSTANTIATE_TEST_SUITE_P(Screens, PulseDemodulatorOnBusyScreens,
                         ::testing::Values(PulseCase{"document", sim::ScreenKind::document},
                                           PulseCase{"web_page", sim::ScreenKind::web_page},
                                           PulseCase{"photo", sim::ScreenKind::photo},
                                           PulseCase{"code_dark", sim::ScreenKind::code_dark}),
                         [](const ::testing::TestParamInfo<PulseCase>& info) { return std::string(info.param.name); });

}  // namespace
