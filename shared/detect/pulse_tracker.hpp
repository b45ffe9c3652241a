// A video's frames searched for the field one by one and together: the
// tracker (tracker.hpp) on each frame, and on the frames where it holds no
// lock the pulse search (pulse_search.hpp) over the frames kept, or the
// place it found last carried to this frame. What a requester that films a
// faintly pulsing screen runs on every camera frame: `umf-requester locate
// --sequence`, the benchmark of a faint pulse, the page.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/detect/tracker.hpp"

namespace umf {

struct PulseTrackResult {
    // The tracker's result, or, where the pulse search found or carried the
    // field, that place as a lock (used_prior: carried).
    TrackResult track;
    bool demodulated = false;  // the place is the pulse search's
    int pulse_frames = 0;      // the frames kept with this one
    double share = 0;          // of their variation the pulse explained, where searched
    double ms = 0;             // the whole update: tracker, registration and search
};

class PulseTracker {
public:
    // The detector must outlive the tracker.
    explicit PulseTracker(const Detector& detector, TrackerOptions tracking = {}, PulseSearchOptions pulse = {});

    // `time_s`: when the frame was taken (PulseSearch::add).
    PulseTrackResult update(const GreyView& frame, const Eigen::Vector2d& aim, std::optional<double> time_s = {});
    PulseTrackResult update(const GreyView& frame);
    void reset();

    const PulseSearch& pulse() const { return pulse_; }

private:
    const Detector* detector_;
    Tracker tracker_;
    PulseSearch pulse_;
};

}  // namespace umf
