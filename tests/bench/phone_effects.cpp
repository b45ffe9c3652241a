#include "tests/bench/phone_effects.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "tests/sim/sequence.hpp"

namespace umf::bench {

// A phone's auto-exposure over a video, as a factor on the light at frame
// `i`: a slow wander (two sines of a few seconds) and, every 2 s or so, a
// re-metering that steps by up to `amplitude` / 2 and settles in about a
// fifth of a second. Within about 1 +- `amplitude`.
double exposure_drift(int i, double amplitude, std::uint64_t seed) {
    if (amplitude <= 0) return 1;
    cv::RNG rng(seed * 7919 + 17);
    const double p1 = rng.uniform(1.1, 2.3), p2 = rng.uniform(2.9, 4.7);
    const double f1 = rng.uniform(0.0, 2 * CV_PI), f2 = rng.uniform(0.0, 2 * CV_PI);
    const double t = i / sim::kFps;
    double factor = 1 + amplitude * (0.35 * std::sin(2 * CV_PI * t / p1 + f1) + 0.25 * std::sin(2 * CV_PI * t / p2 + f2));
    for (double at = rng.uniform(0.5, 1.5); at <= t; at += rng.uniform(1.5, 2.5)) {
        const double step = amplitude * rng.uniform(-0.5, 0.5);
        factor += step * (1 - std::exp(-(t - at) / 0.07));
    }
    return std::clamp(factor, 1 - 1.5 * amplitude, 1 + 1.5 * amplitude);
}

// Row y of `frame` as a rolling shutter reads it: at the pose a fraction
// of the way from this frame's towards the next frame's (`to_next`: their
// screen-to-image homographies, `interval_s` apart), the fraction the row's
// read-out time after the middle row's; rows above the middle read before.
// The homographies are interpolated entry by entry (normalised), close to
// the poses' own interpolation over the few milliseconds of a read-out.
// Not sim::rolling_shutter: that is the held-out camera's, and a tuning
// video made with it would tune on the held-out camera's own effect.
void roll_shutter(cv::Mat& frame, const cv::Matx33d& at_frame, const cv::Matx33d& to_next, double interval_s,
                  double readout_s) {
    const cv::Matx33d a = at_frame * (1 / at_frame(2, 2)), b = to_next * (1 / to_next(2, 2));
    cv::Mat map_x(frame.size(), CV_32F), map_y(frame.size(), CV_32F);
    for (int y = 0; y < frame.rows; ++y) {
        const double s = (y - (frame.rows - 1) / 2.0) / frame.rows * readout_s / interval_s;
        // The row's image point back to the frame as shot at once.
        const cv::Matx33d back = a * (a + s * (b - a)).inv();
        for (int x = 0; x < frame.cols; ++x) {
            const cv::Vec3d p = back * cv::Vec3d(x, y, 1);
            map_x.at<float>(y, x) = static_cast<float>(p[0] / p[2]);
            map_y.at<float>(y, x) = static_cast<float>(p[1] / p[2]);
        }
    }
    cv::Mat rolled;
    cv::remap(frame, rolled, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    frame = rolled;
}

}  // namespace umf::bench
