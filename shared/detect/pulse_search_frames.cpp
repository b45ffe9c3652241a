// The frames a pulse search keeps: each registered onto the last as it
// comes, one that cannot be set aside and stepped across, a cut started
// over from (pulse_search.hpp).
#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "shared/detect/homography.hpp"
#include "shared/detect/pulse_search.hpp"

namespace umf {

namespace {

// How far apart (pixels) two homographies put a corner of a w x h frame.
double corner_distance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, int w, int h) {
    double most = 0;
    for (const double x : {0.0, w - 1.0})
        for (const double y : {0.0, h - 1.0}) {
            const auto p = apply_homography(a, Point2(x, y)), q = apply_homography(b, Point2(x, y));
            if (!p || !q) return std::numeric_limits<double>::infinity();
            most = std::max(most, (*p - *q).norm());
        }
    return most;
}

}  // namespace

void PulseSearch::add(const GreyView& frame, std::optional<double> time_s) {
    if (auto problem = describe_invalid(frame); !problem.empty()) throw std::invalid_argument("pulse search: " + problem);
    if (frame.width != width_ || frame.height != height_) {
        clear();
        width_ = frame.width;
        height_ = frame.height;
    }
    if (time_s && !std::isfinite(*time_s)) time_s.reset();
    // A clock that stands or runs back (a page's timestamps from another
    // source after a restart) cannot place the pulse: the frames kept
    // before it are dropped.
    const std::optional<double> newest_time = stray_         ? stray_->time_s
                                              : kept_.empty() ? std::nullopt
                                                              : kept_.back().time_s;
    if (!kept_.empty() && time_s && newest_time && !(*time_s > *newest_time)) {
        kept_.clear();
        stray_.reset();
        found_.reset();
    }
    Kept next{FramePyramid(frame), Eigen::Matrix3d::Identity(), time_s, added_++};
    last_registration_ = {};
    last_span_ = 1;
    if (!kept_.empty()) {
        // Across the frame set aside, if any: the view has come twice as far.
        const int gap = stray_ ? 2 : 1;
        FrameRegistration r = register_next(next.pyramid, gap);
        int came = gap;
        if (!r.registered && stray_) {
            // Two frames in a row that cannot be laid onto the frames kept:
            // the view has moved on (a cut), and starts over from the first.
            start_over_from_stray();
            r = register_next(next.pyramid, 1);
            came = 1;
        }
        last_registration_ = r;
        last_span_ = came;
        if (!r.registered) {
            // Set aside for the next frame to be laid across. Whether it
            // was refused with its alignment in step with the hand: a frame
            // smeared by the hand differs from the last in its grey levels,
            // not in where it lies.
            stray_in_step_ = motion_ && r.homography.allFinite() &&
                             r.overlap >= options_.registration.min_overlap && in_step(r.homography, *motion_, 1);
            stray_ = std::move(next);
            ++unregistered_;
            ++added_since_search_;
            return;
        }
        stray_.reset();
        // The first registration after a start has no motion to be
        // checked against (max_motion_change): the frames are kept, but
        // a place is not carried through an alignment that may have
        // slid a line of text or a module along.
        const bool checked = motion_.has_value();
        // Across a frame set aside, the motion of one frame is left as it
        // was: the next frame's first guess.
        earlier_motion_ = came == 1 ? motion_ : std::nullopt;
        if (came == 1) motion_ = r.homography;
        for (Kept& k : kept_) k.to_newest = r.homography * k.to_newest;
        if (found_) found_->image_to_field = found_->image_to_field * r.homography.inverse();
        // Nor through one aligned on the frames' detail alone: content
        // the grey levels could not align (a tiled board's repeats, a
        // glare) may be aligned a little off, frame after frame.
        through_detail_ = through_detail_ || r.on_detail;
        carried_for_ += came;
        // Nor across a frame set aside whose own alignment did not keep to
        // the hand's motion (on a blank page, one aligned tens of pixels
        // off): the alignment across it may be as far off.
        if (carried_for_ > options_.carry_frames || !checked || (came > 1 && !stray_in_step_) ||
            (through_detail_ && !near_found()))
            found_.reset();
    }
    if (kept_.empty()) {
        // No motion to start the next frame's registration from.
        motion_.reset();
        earlier_motion_.reset();
    }
    if (static_cast<int>(kept_.size()) >= options_.frames) kept_.pop_front();
    kept_.push_back(std::move(next));
    ++added_since_search_;
}

bool PulseSearch::in_step(const Eigen::Matrix3d& motion, const Eigen::Matrix3d& guess, int gap) const {
    return corner_distance(motion, guess, width_, height_) <= gap * options_.max_motion_change * width_;
}

void PulseSearch::start_over_from_stray() {
    kept_.clear();
    found_.reset();
    motion_.reset();
    earlier_motion_.reset();
    kept_.push_back(std::move(*stray_));
    kept_.back().to_newest = Eigen::Matrix3d::Identity();
    stray_.reset();
}

FrameRegistration PulseSearch::register_next(const FramePyramid& next, int gap) const {
    const FramePyramid& last = kept_.back().pyramid;
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    // From where the view stands: made once, whichever guess needs it.
    std::optional<FrameRegistration> standing;
    // From `guess`, else from where the view stands (a view that stops or
    // turns back); a motion too far from the guess is taken for none (across
    // a frame set aside, the hand has had as many frames to change it),
    // unless the frames say where they lie: the alignment from the guess
    // is within kOutOfStepReach times the change allowed, leaves far less
    // unexplained than the guess does, and the alignment from where the view
    // stands comes to the same place (on a page with little to align on,
    // where an alignment ends hangs on where it began).
    auto checked = [&](FrameRegistration r, const Eigen::Matrix3d& guess, const RegistrationOptions& options,
                       bool from_guess) {
        if (!r.registered || guess.isIdentity() || in_step(r.homography, guess, gap)) return r;
        r.registered = false;
        if (!from_guess || !in_step(r.homography, guess, kOutOfStepReach * gap) ||
            !(r.residual <= options_.out_of_step_share * r.guess_residual))
            return r;
        // From where the view stands with the same options: the first
        // attempt's, made once, or a retry's own.
        FrameRegistration from_standing;
        if (&options == &options_.registration) {
            if (!standing) standing = register_frames(last, next, identity, options);
            from_standing = *standing;
        } else {
            from_standing = register_frames(last, next, identity, options);
        }
        r.registered = from_standing.registered &&
                       corner_distance(from_standing.homography, r.homography, width_, height_) <= kSameAlignmentPx;
        return r;
    };
    auto attempt = [&](const Eigen::Matrix3d& guess) {
        FrameRegistration r = register_frames(last, next, guess, options_.registration);
        bool from_guess = true;
        if (!r.registered && !guess.isIdentity()) {
            if (!standing) standing = register_frames(last, next, identity, options_.registration);
            r = *standing;
            from_guess = false;
        }
        r = checked(r, guess, options_.registration, from_guess);
        // Lines of text can draw the whole homography a line along at the
        // coarsest level: aligned again with an affine change there.
        if (!r.registered && options_.affine_retry && !options_.registration.affine_coarse) {
            RegistrationOptions affine = options_.registration;
            affine.affine_coarse = true;
            FrameRegistration a = checked(register_frames(last, next, guess, affine), guess, affine, true);
            if (a.registered) r = a;
        }
        if (!r.registered && options_.detail_retry && !options_.registration.detail) {
            RegistrationOptions detail = options_.registration;
            detail.detail = true;
            FrameRegistration d = checked(register_frames(last, next, guess, detail), guess, detail, true);
            if (d.registered) r = d;
        }
        return r;
    };
    // The last motion is the likeliest next one; a hand speeding up or
    // slowing down goes on changing its motion as it did, so that change
    // carried on is tried too where it differs, and the alignment leaving
    // the smaller residual kept.
    Eigen::Matrix3d last_motion = identity;
    if (motion_)
        for (int i = 0; i < gap; ++i) last_motion = *motion_ * last_motion;
    last_motion /= last_motion(2, 2);
    FrameRegistration best = attempt(last_motion);
    if (motion_ && earlier_motion_ && gap == 1) {
        Eigen::Matrix3d carried_on = *motion_ * earlier_motion_->inverse() * *motion_;
        carried_on /= carried_on(2, 2);
        if (corner_distance(carried_on, last_motion, width_, height_) > kSameGuessPx) {
            FrameRegistration r = attempt(carried_on);
            if (r.registered && (!best.registered || r.residual < best.residual)) best = r;
        }
    }
    return best;
}

}  // namespace umf
