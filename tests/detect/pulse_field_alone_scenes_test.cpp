// The field alone (PulseSearchOptions::field_alone) on a simulated photo of
// a camera at rest before a dark code editor: content as strong as the
// field hides it in the demodulated slope, and the frames followed out to
// opacity 1, where the pulse's range is announced, show it. The camera
// simulator makes this slow under the sanitizers, which run
// pulse_demodulator_test.cpp instead.
#include <gtest/gtest.h>

#include <cmath>

#include "shared/detect/detector.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

// 12 frames at rest of the dark code, its field pulsing between 0.01 and
// 0.04 from 0.4 s into the pulse (past the rise's middle, over the top).
// Of the five screen kinds filmed at three starts, this is where the slope
// image and its inverse held no field and the field alone did.
TEST(PulseSearch, FindsTheFieldAloneWhereTheContentHidesItsSlope) {
    const Field field = test::shipped_field("b4-64x36.json");
    const Detector detector(field);
    test::Photo p = test::resting_phone();
    const auto frames =
        test::film_pulse(field, p, sim::ScreenKind::code_dark, test::sine_pulse(0.01, 0.04, 1.5), 12, 0.4);
    const cv::Point2d truth = sim::image_to_field(p.shot, p.placement, {320, 240});
    auto search_with = [&](const PulseShape& shape, bool alone, bool content_free = false) {
        PulseSearchOptions options;
        options.shape = shape;
        options.field_alone = alone;
        if (!content_free) options.content_free_tile = 0;
        PulseSearch search(options);
        for (const cv::Mat& frame : frames) search.add(test::grey_view(frame));
        return search.search(detector, {320, 240});
    };
    const PulseShape announced = overlay::announced_pulse_shape(overlay::Waveform::sine, 1.5, 0.01, 0.04);
    const PulseShape unranged = overlay::announced_pulse_shape(overlay::Waveform::sine, 1.5);
    const PulseSearchResult alone = search_with(announced, true);
    ASSERT_TRUE(alone.detection.found) << alone.detection.failure;
    EXPECT_TRUE(alone.fitted);
    EXPECT_LT(std::hypot(alone.detection.aim_field.x() - truth.x, alone.detection.aim_field.y() - truth.y), 0.05);
    EXPECT_FALSE(search_with(announced, false).detection.found) << "the slope alone";
    EXPECT_FALSE(search_with(unranged, true).detection.found) << "the range not announced";
    // The slope with the content's leakage taken out (content_leakage.hpp)
    // needs no range: it finds the field here too, at the same place.
    const PulseSearchResult free = search_with(unranged, true, true);
    ASSERT_TRUE(free.detection.found) << free.detection.failure;
    EXPECT_LT(std::hypot(free.detection.aim_field.x() - truth.x, free.detection.aim_field.y() - truth.y), 0.05);
}

}  // namespace
