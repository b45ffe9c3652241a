// The pulse's demodulation on simulated photos of a camera at rest before
// busy screens whose field pulses at a few percent (pulse_demodulator.hpp,
// pulse_course.hpp, pulse_search.hpp); a hand-held phone's frames are
// pulse_hand_held_scenes_test.cpp's. The camera simulator makes these
// slow under the sanitizers, which run pulse_demodulator_test.cpp instead.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/pulse_course.hpp"
#include "shared/detect/pulse_demodulator.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using test::grey_view;

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

// A phone at rest before a web page whose field pulses between 0.01 and
// 0.04 (sine, 1.5 s) at 25 frames a second, from `start_s` into the pulse;
// opacity `steady` >= 0 instead holds the field still.
struct Clip {
    std::vector<cv::Mat> frames;
    cv::Point2d truth;  // the field point under the image centre
};

Clip film(const Field& f, int count, double start_s, double steady = -1) {
    test::Photo p = test::resting_phone();
    const overlay::Preset pulse = steady >= 0 ? test::sine_pulse(steady, steady, 1.5) : test::sine_pulse(0.01, 0.04, 1.5);
    Clip clip;
    clip.frames = test::film_pulse(f, p, sim::ScreenKind::web_page, pulse, count, start_s);
    clip.truth = sim::image_to_field(p.shot, p.placement, {320, 240});
    return clip;
}

class PulseSearchOnAWebPage : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        field_ = new Field(test::shipped_field("b4-64x36.json"));
        pulsing_ = new Clip(film(*field_, 16, 0.9));  // past the top, falling, and rising again
    }
    static void TearDownTestSuite() {
        delete pulsing_;
        delete field_;
    }
    static inline Field* field_ = nullptr;
    static inline Clip* pulsing_ = nullptr;
};

TEST_F(PulseSearchOnAWebPage, FindsTheFieldOnceEnoughFramesAreKept) {
    const Detector detector(*field_);
    PulseSearchOptions options;
    options.frames = 12;  // the last 12 of 16: the oldest are dropped
    PulseSearch search(options);
    const Eigen::Vector2d aim(320, 240);
    for (int i = 0; i < 16; ++i) {
        search.add(grey_view(pulsing_->frames[static_cast<std::size_t>(i)]));
        if (i == 5) {
            const PulseSearchResult early = search.search(detector, aim);
            EXPECT_FALSE(early.detection.found);
            EXPECT_EQ(early.detection.failure, "too few frames for the pulse");
        }
    }
    EXPECT_EQ(search.frames(), 12);
    const PulseSearchResult r = search.search(detector, aim);
    ASSERT_TRUE(r.detection.found) << r.detection.failure << ", share " << r.share;
    EXPECT_FALSE(r.fitted);
    EXPECT_GT(r.share, 0.2);
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
              0.05);
}

TEST_F(PulseSearchOnAWebPage, FitsTheAnnouncedShape) {
    const Detector detector(*field_);
    PulseSearchOptions options;
    options.shape = overlay::announced_pulse_shape(overlay::Waveform::sine, 1.5);
    PulseSearch search(options);
    for (const cv::Mat& frame : pulsing_->frames) search.add(grey_view(frame));
    const PulseSearchResult r = search.search(detector, {320, 240});
    ASSERT_TRUE(r.detection.found) << r.detection.failure;
    EXPECT_TRUE(r.fitted);
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
              0.05);
    // A shape the frames do not follow (a period of 0.2 s) is not taken.
    options.shape->period_s = 0.2;
    options.frame_rates = {25};
    PulseSearch wrong(options);
    for (const cv::Mat& frame : pulsing_->frames) wrong.add(grey_view(frame));
    const PulseSearchResult w = wrong.search(detector, {320, 240});
    EXPECT_FALSE(w.fitted);
    EXPECT_TRUE(w.detection.found) << "the course itself is used";
}

// The phone's auto-exposure wanders by a few percent while the field pulses
// by as much: the frames' main course over time is the exposure's unless
// each frame is levelled to one exposure first.
TEST_F(PulseSearchOnAWebPage, LevelsTheExposureBeforeDemodulating) {
    const Detector detector(*field_);
    std::vector<cv::Mat> drifting;
    for (std::size_t i = 0; i < pulsing_->frames.size(); ++i) {
        cv::Mat m;
        pulsing_->frames[i].convertTo(m, CV_8U, 1 + 0.05 * std::sin(0.9 * static_cast<double>(i) + 1));
        drifting.push_back(m);
    }
    for (const bool level : {true, false}) {
        PulseSearchOptions options;
        options.level_exposure = level;
        PulseSearch search(options);
        for (const cv::Mat& frame : drifting) search.add(grey_view(frame));
        const PulseSearchResult r = search.search(detector, {320, 240});
        if (!level) {
            EXPECT_FALSE(r.detection.found) << "the course is the exposure's";
            continue;
        }
        ASSERT_TRUE(r.detection.found) << r.detection.failure << ", share " << r.share;
        EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
                  0.05);
    }
}

TEST_F(PulseSearchOnAWebPage, AFieldThatDoesNotPulseIsNotSearched) {
    const Detector detector(*field_);
    const Clip steady = film(*field_, 10, 0, 0.03);
    PulseSearch search;
    for (const cv::Mat& frame : steady.frames) search.add(grey_view(frame));
    const PulseSearchResult r = search.search(detector, {320, 240});
    EXPECT_FALSE(r.detection.found);
    EXPECT_EQ(r.detection.failure, "no pulse in the frames");
    EXPECT_LT(r.share, 0.2);
    // Another size starts over.
    cv::Mat small(240, 320, CV_8U, cv::Scalar(90));
    search.add(grey_view(small));
    EXPECT_EQ(search.frames(), 1);
}

}  // namespace
