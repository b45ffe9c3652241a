#include "shared/detect/tracker.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <span>

namespace umf {

const char* to_string(TrackState state) {
    switch (state) {
        case TrackState::searching: return "searching";
        case TrackState::locked: return "locked";
        case TrackState::lost: return "lost";
    }
    return "?";
}

Tracker::Tracker(const Detector& detector, TrackerOptions options) : detector_(&detector), options_(options) {}

void Tracker::reset() {
    has_prior_ = false;
    frames_since_lock_ = 0;
    has_motion_ = false;
    next_piece_ = 0;
    finding_first_piece_ = 0;
    finding_pieces_ = 0;
    next_step_ = 0;
    first_scan_from_ = 0;
    finding_piece_ = -1;
    finding_step_ = 0;
    finding_first_step_ = 0;
}

Detection Tracker::spread_search(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                 bool use_prior) {
    // The round goes on where it stopped, across locks; while the prior
    // holds, every other frame retries the share that found the last lock
    // (a faint field that only a late piece finds is lost again at its
    // pulse's faint phase, and a round starting over at every lock would
    // take most of a round to reach that piece again).
    if (options_.frame_ms > 0) return timed_search(image, aim, prior, use_prior);
    const bool retry = finding_pieces_ > 0 && use_prior && frames_since_lock_ % 2 == 0;
    const double budget = options_.search_budget;
    const ScheduledSearch share = retry ? search_share(finding_first_piece_, budget, finding_pieces_)
                                        : search_share(next_piece_, budget);
    if (!retry) next_piece_ = (share.first_piece + share.pieces) % kRoundPieces;
    Detection d = detector_->detect(image, aim, prior, std::span<const SearchPlan>(share.plans.data(), share.count));
    if (d.found) {
        finding_first_piece_ = share.first_piece;
        finding_pieces_ = share.pieces;
    }
    return d;
}

Detection Tracker::timed_search(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                bool use_prior) {
    // The first scan, then the round from where the last frame stopped to
    // its end, held to frame_ms, a step of it at least (a first scan that
    // alone takes the time, as on a page dense with text or rules, would
    // otherwise stall the round); a retry (as above) runs the piece that
    // found the last lock from the step that found it.
    //
    // With hold_first_scan: the first scan's search of the part around the
    // aim whatever the time, then, one step at least, the first scan's
    // searches of the whole frame, taken up where the last frame stopped,
    // and the round. A frame that ends the whole frame's searches with no
    // time for the round gives the next frame to the round. A retry runs
    // the piece that found the last lock after the search around the aim
    // alone, or the whole frame's first scan from the step that found it.
    const bool retry =
        (finding_piece_ >= 0 || finding_first_step_ > 0) && use_prior && frames_since_lock_ % 2 == 0;
    const bool retry_piece = retry && finding_piece_ >= 0;
    const int from = retry ? std::max(0, finding_piece_) : next_piece_;
    const int to = retry ? (retry_piece ? finding_piece_ + 1 : 0) : kRoundPieces;
    std::array<SearchPlan, kRoundPieces + 1> plans{};
    std::size_t count = 0;
    plans[count] = spread_first();
    plans[count++].near_aim_alone = options_.hold_first_scan && (retry_piece || (!retry && first_scan_from_ < 0));
    for (int k = from; k < to; ++k) plans[count++] = kSpreadRound[static_cast<std::size_t>(k)].plan();
    SearchLimit limit;
    limit.ms = options_.frame_ms;
    limit.skip_steps = retry ? finding_step_ : next_step_;
    limit.min_steps = 1;
    if (options_.hold_first_scan) {
        limit.first_min_steps = kFirstStepsEveryFrame;
        limit.first_ms = options_.frame_ms * options_.first_scan_times;
        limit.first_skip_steps = retry ? finding_first_step_ : std::max(0, first_scan_from_);
        limit.as_dear_as_dearest = true;
    }
    Detection d = detector_->detect(image, aim, prior, std::span<const SearchPlan>(plans.data(), count), limit);
    if (!retry)
        first_scan_from_ = d.found                                                  ? 0
                           : limit.first_steps_into_next > 0                        ? limit.first_steps_into_next
                           : limit.first_held_steps_run > 0 && limit.steps_run == 0 ? -1
                                                                                    : 0;
    if (d.found) {
        finding_piece_ = limit.found_plan > 0 ? from + limit.found_plan - 1 : -1;
        finding_step_ = std::max(0, limit.found_step);
        // Found by the whole frame's first scan (a ruled page's field, off
        // its rules: its last step): the retry takes it up there.
        finding_first_step_ = options_.hold_first_scan && limit.found_plan == 0 &&
                                      limit.found_step >= kFirstStepsEveryFrame
                                  ? limit.found_step
                                  : 0;
    }
    // The first scan's find leaves the round where it was.
    if (retry || limit.found_plan == 0) return d;
    next_piece_ = from + limit.plans_done;
    next_step_ = d.found && limit.found_plan > 0 ? limit.found_step + 1 : limit.steps_into_next;
    if (next_piece_ >= kRoundPieces) next_piece_ = 0, next_step_ = 0;
    return d;
}

TrackResult Tracker::update(const GreyView& image) {
    return update(image, Eigen::Vector2d(image.width / 2.0, image.height / 2.0));
}

TrackResult Tracker::update(const GreyView& image, const Eigen::Vector2d& aim) {
    TrackResult out;
    const bool use_prior = has_prior_ && frames_since_lock_ <= options_.prior_frames;
    DetectionPrior prior;
    if (use_prior) {
        prior.image_to_field = last_image_to_field_;
        // The place may drift further the longer it has not been seen.
        prior.radius_modules = options_.search_radius_modules + frames_since_lock_ / 2;
    }
    if (has_prior_ && frames_since_lock_ < options_.follow_frames) {
        // The image keeps moving as it moved between the last two locked
        // frames: A_t = A_{t-1} D with D = A_{t-2}^-1 A_{t-1} for
        // image-to-field maps A, once per frame since the last lock.
        Eigen::Matrix3d predicted = last_image_to_field_;
        if (has_motion_)
            for (int k = 0; k <= frames_since_lock_; ++k) predicted = predicted * motion_;
        out.detection = detector_->follow(image, aim, predicted);
    }
    if (!out.detection.found) {
        const double followed_ms = out.detection.times.total_ms;
        const DetectionPrior* p = use_prior ? &prior : nullptr;
        if (options_.spread_search) {
            out.detection = spread_search(image, aim, p, use_prior);
        } else {
            out.detection = detector_->detect(image, aim, p);
        }
        out.detection.times.total_ms += followed_ms;
    }
    const Detection& d = out.detection;
    if (!d.found) {
        ++frames_since_lock_;
        out.frames_since_lock = frames_since_lock_;
        out.state = has_prior_ && frames_since_lock_ <= options_.prior_frames ? TrackState::lost : TrackState::searching;
        return out;
    }
    out.used_prior = d.from_prior;
    out.state = TrackState::locked;
    // Smooth only a resting aim, and only across consecutive frames: a moving
    // aim or a gap would make the smoothed point one nobody pointed at.
    const bool continuous = has_prior_ && frames_since_lock_ == 0;
    const double moved = (d.aim_field - last_raw_aim_).norm();
    if (continuous && moved < options_.still_modules) {
        smoothed_ = options_.smoothing * d.aim_field + (1 - options_.smoothing) * smoothed_;
        const Eigen::Vector2d lag = smoothed_ - d.aim_field;
        if (lag.norm() > options_.max_lag_modules) smoothed_ = d.aim_field + lag.normalized() * options_.max_lag_modules;
    } else {
        smoothed_ = d.aim_field;
    }
    out.aim_field = smoothed_;
    last_raw_aim_ = d.aim_field;
    // The motion per frame is known from two locks in a row only.
    // A map found at another size, or on the frame smoothed, is right at the
    // aim but coarser elsewhere: the motion taken from it would throw the
    // next predictions off.
    const bool full_size = d.size_scale == 1 && !d.from_smoothed;
    has_motion_ = continuous && full_size && last_full_size_;
    last_full_size_ = full_size;
    if (has_motion_) motion_ = last_image_to_field_.inverse() * d.image_to_field;
    last_image_to_field_ = d.image_to_field;
    has_prior_ = true;
    frames_since_lock_ = 0;
    return out;
}

}  // namespace umf
