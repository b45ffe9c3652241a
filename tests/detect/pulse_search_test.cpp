#include "shared/detect/pulse_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

// A phone at rest before a web page whose field pulses between 0.01 and
// 0.04 (sine, 1.5 s) at 25 frames a second, from `start_s` into the pulse;
// opacity `steady` >= 0 instead holds the field still.
struct Clip {
    std::vector<cv::Mat> frames;
    cv::Point2d truth;  // the field point under the image centre
};

Clip film(const Field& f, int count, double start_s, double steady = -1) {
    test::Photo p;
    p.camera.resolution = {640, 480};
    p.pose.distance_mm = 320;
    p.pose.pitch_deg = -10;
    p.pose.yaw_deg = 14;
    p.pose.roll_deg = -20;
    p.pose.aim_screen_px = {900, 560};
    const overlay::Preset pulse = steady >= 0 ? test::sine_pulse(steady, steady, 1.5) : test::sine_pulse(0.01, 0.04, 1.5);
    Clip clip;
    clip.frames = test::film_pulse(f, p, sim::ScreenKind::web_page, pulse, count, start_s);
    clip.truth = sim::image_to_field(p.shot, p.placement, {320, 240});
    return clip;
}

GreyView view(const cv::Mat& m) { return {m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)}; }

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
        search.add(view(pulsing_->frames[static_cast<std::size_t>(i)]));
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
    overlay::Preset unit;  // the pulse's shape: 0 to 1 over a period
    unit.opacity_min = 0;
    unit.opacity_max = 1;
    unit.period_s = 1;
    options.shape = PulseShape{[unit](double phase) { return overlay::opacity_at(unit, phase); }, 1.5};
    PulseSearch search(options);
    for (const cv::Mat& frame : pulsing_->frames) search.add(view(frame));
    const PulseSearchResult r = search.search(detector, {320, 240});
    ASSERT_TRUE(r.detection.found) << r.detection.failure;
    EXPECT_TRUE(r.fitted);
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
              0.05);
    // A shape the frames do not follow (a period of 0.2 s) is not taken.
    options.shape->period_s = 0.2;
    options.frame_rates = {25};
    PulseSearch wrong(options);
    for (const cv::Mat& frame : pulsing_->frames) wrong.add(view(frame));
    const PulseSearchResult w = wrong.search(detector, {320, 240});
    EXPECT_FALSE(w.fitted);
    EXPECT_TRUE(w.detection.found) << "the course itself is used";
}

TEST_F(PulseSearchOnAWebPage, AFieldThatDoesNotPulseIsNotSearched) {
    const Detector detector(*field_);
    const Clip steady = film(*field_, 10, 0, 0.03);
    PulseSearch search;
    for (const cv::Mat& frame : steady.frames) search.add(view(frame));
    const PulseSearchResult r = search.search(detector, {320, 240});
    EXPECT_FALSE(r.detection.found);
    EXPECT_EQ(r.detection.failure, "no pulse in the frames");
    EXPECT_LT(r.share, 0.2);
    // Another size starts over.
    cv::Mat small(240, 320, CV_8U, cv::Scalar(90));
    search.add(view(small));
    EXPECT_EQ(search.frames(), 1);
}

TEST(PulseSearch, AViewThatMovesIsNotSearched) {
    // A phone turning slowly over a web page with a steady field (each frame
    // a third of a degree on): its frames hold no still pulse to demodulate,
    // and demodulating them would cost a frame 70 ms for nothing.
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    std::vector<cv::Mat> frames;
    for (int i = 0; i < 10; ++i) {
        const test::Photo p = test::photograph_field(f, 0.03, 10 + i * 0.3, 5 - i * 0.2, 20 + i * 0.5, 300,
                                                     sim::ScreenKind::web_page);
        frames.push_back(p.shot.grey.clone());
    }
    PulseSearch search;
    for (const cv::Mat& frame : frames) search.add(view(frame));
    EXPECT_TRUE(search.due());
    const PulseSearchResult r = search.search(detector, {320, 240});
    EXPECT_FALSE(r.detection.found);
    EXPECT_EQ(r.detection.failure, "the view moved");
    EXPECT_FALSE(search.due()) << "not again before search_every more frames";
    for (int i = 0; i < 4; ++i) search.add(view(frames[static_cast<std::size_t>(i)]));
    EXPECT_TRUE(search.due());
}

}  // namespace
