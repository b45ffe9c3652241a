#include "shared/detect/pulse_tracker.hpp"

#include "shared/detect/stage_time.hpp"

namespace umf {

PulseTracker::PulseTracker(const Detector& detector, TrackerOptions tracking, PulseSearchOptions pulse)
    : detector_(&detector), tracker_(detector, tracking), pulse_(std::move(pulse)) {}

void PulseTracker::reset() {
    tracker_.reset();
    pulse_.clear();
}

PulseTrackResult PulseTracker::update(const GreyView& frame) {
    return update(frame, Eigen::Vector2d(frame.width / 2.0, frame.height / 2.0));
}

PulseTrackResult PulseTracker::update(const GreyView& frame, const Eigen::Vector2d& aim, std::optional<double> time_s) {
    auto start = StageClock::now();
    PulseTrackResult out;
    out.track = tracker_.update(frame, aim);
    // Every frame is kept, locked or not: a lock lost in the pulse's faint
    // phase needs the frames before it, registered onto each other.
    pulse_.add(frame, time_s);
    out.pulse_frames = pulse_.frames();
    if (out.track.state == TrackState::locked) {
        // The freshest place to carry into the frames after, should the
        // lock be lost in the pulse's faint phase: a search's from frames
        // ago has come through more registrations, each a little off.
        pulse_.found_elsewhere(out.track.detection);
    } else {
        std::optional<Detection> found;
        if (pulse_.due()) {
            PulseSearchResult r = pulse_.search(*detector_, aim);
            out.share = r.share;
            if (r.detection.found) found = std::move(r.detection);
        }
        if (!found) {
            found = pulse_.carried(aim);
            if (found && !pulse_.holds_in_newest(*found, detector_->field())) found.reset();
        }
        if (found) {
            out.demodulated = true;
            out.track.state = TrackState::locked;
            out.track.aim_field = found->aim_field;
            out.track.used_prior = found->from_prior;
            out.track.frames_since_lock = 0;
            out.track.detection = std::move(*found);
        }
    }
    out.ms = ms_since(start);
    return out;
}

}  // namespace umf
