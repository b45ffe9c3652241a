// The pulse search given each frame's time: a page's frames, kept unevenly.
// Photographs: left out of the sanitizer build, as pulse_scenes_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numeric>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using test::grey_view;

// A page that is busy drops camera frames: the frames kept come at uneven
// times, and the announced shape is fitted at each frame's own time, not at
// any frame rate (those tried here, 50 a second, are wrong).
TEST(PulseSearch, FitsTheAnnouncedShapeAtEachFramesOwnTime) {
    const Field f = test::shipped_field("b4-64x36.json");
    test::Photo p = test::resting_phone();
    const std::vector<cv::Mat> frames =
        test::film_pulse(f, p, sim::ScreenKind::web_page, test::sine_pulse(0.01, 0.04, 1.5), 36, 0.9);
    const cv::Point2d truth_at_centre = sim::image_to_field(p.shot, p.placement, {320, 240});
    const std::vector<int> taken = {0, 1, 2, 5, 6, 9, 13, 14, 15, 19, 22, 23, 27, 30, 31, 35};
    const Detector detector(f);
    PulseSearchOptions options;
    options.shape = overlay::announced_pulse_shape(overlay::Waveform::sine, 1.5);
    options.frame_rates = {50};
    std::vector<double> truth;
    for (const int i : taken) truth.push_back(overlay::opacity_at(test::sine_pulse(0.01, 0.04, 1.5), 0.9 + i / 25.0));
    auto followed = [&](const std::vector<double>& course) {
        if (course.size() != truth.size()) return 0.0;
        const double mc = std::accumulate(course.begin(), course.end(), 0.0) / course.size();
        const double mt = std::accumulate(truth.begin(), truth.end(), 0.0) / truth.size();
        double ct = 0, cc = 0, tt = 0;
        for (std::size_t i = 0; i < course.size(); ++i) {
            ct += (course[i] - mc) * (truth[i] - mt);
            cc += (course[i] - mc) * (course[i] - mc);
            tt += (truth[i] - mt) * (truth[i] - mt);
        }
        return ct / std::sqrt(cc * tt);
    };
    PulseSearch timed(options), untimed(options);
    for (const int i : taken) {
        timed.add(grey_view(frames[static_cast<std::size_t>(i)]), 1000.0 + i / 25.0);
        untimed.add(grey_view(frames[static_cast<std::size_t>(i)]));
    }
    const PulseSearchResult r = timed.search(detector, {320, 240});
    ASSERT_TRUE(r.detection.found) << r.detection.failure;
    EXPECT_TRUE(r.fitted);
    EXPECT_GT(std::abs(followed(r.course)), 0.99);
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - truth_at_centre.x, r.detection.aim_field.y() - truth_at_centre.y), 0.05);
    const PulseSearchResult u = untimed.search(detector, {320, 240});
    std::cout << "[ measure  ] the course's correlation with the pulse at the frames' times: timed " << followed(r.course)
              << ", at 50 frames a second " << followed(u.course) << "\n";
    EXPECT_LT(std::abs(followed(u.course)), 0.95) << "fitted at the rate tried, not the frames' times";
    // A clock that runs back starts the frames kept over.
    timed.add(grey_view(frames.back()), 999.0);
    EXPECT_EQ(timed.frames(), 1);
}

}  // namespace
