// What a hand-held phone adds to the tuning set's pulsing videos beyond the
// simulator's shot (umf_pulse_benchmark's --exposure-drift and
// --rolling-shutter): its auto-exposure over time, and the rows of a frame
// read one after another.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

namespace umf::bench {

// A phone's auto-exposure over a video, as a factor on the light at frame
// `i`: a slow wander (two sines of a few seconds) and, every 2 s or so, a
// re-metering that steps by up to `amplitude` / 2 and settles in about a
// fifth of a second. Within about 1 +- `amplitude`.
double exposure_drift(int i, double amplitude, std::uint64_t seed);

// Row y of `frame` as a rolling shutter reads it: at the pose a fraction
// of the way from this frame's towards the next frame's (`to_next`: their
// screen-to-image homographies, `interval_s` apart), the fraction the row's
// read-out time after the middle row's; rows above the middle read before.
// The homographies are interpolated entry by entry (normalised), close to
// the poses' own interpolation over the few milliseconds of a read-out.
// Not sim::rolling_shutter: that is the held-out camera's, and a tuning
// video made with it would tune on the held-out camera's own effect.
void roll_shutter(cv::Mat& frame, const cv::Matx33d& at_frame, const cv::Matx33d& to_next, double interval_s,
                  double readout_s);

}  // namespace umf::bench
