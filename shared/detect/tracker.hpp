// Detection over a video: the last verified places predict where the field
// is (at constant image velocity), so the next frame only has to confirm it
// there (Detector::follow: no search, the field's own edges refit, a handful
// of hypotheses instead of every window of the field in four turns), which
// needs far less evidence and so survives lower opacity, blur and the faint
// half of a pulse. When that fails, full detection, with the prior. The aim point is smoothed while it holds still and
// follows at once when it moves. A frame that cannot be verified reports no
// place ("lost"), never an extrapolated one: a wrong document is worse than
// a moment without one.
#pragma once

#include <Eigen/Core>

#include "shared/detect/detector.hpp"

namespace umf {

// The share of the time between two camera frames that a requester in real
// time gives the spread search (TrackerOptions::frame_ms): the rest is for
// taking the frame from the camera, the page's drawing and the follow.
inline constexpr double kSpreadFrameShare = 0.5;

// The steps of spread_first() that a frame held to frame_ms with
// hold_first_scan runs whatever the time: the search of the part around the
// aim (the small-modules cue's lattice and its three edgel sets), which
// finds most fields for a quarter of the first scan's cost.
inline constexpr int kFirstStepsEveryFrame = 4;

struct TrackerOptions {
    // Frames after the last lock during which the prior is still used.
    int prior_frames = 12;
    // Frames after the last lock during which the place is still predicted
    // and followed (at the last motion) before a search.
    int follow_frames = 4;
    // How far (in modules, at the aim point) the field may have moved
    // between the prior's frame and this one.
    int search_radius_modules = 3;
    // Smoothing of the reported aim point: the new point's weight while the
    // aim moves less than `still_modules` per frame; above that the aim
    // follows unsmoothed.
    double smoothing = 0.4;
    double still_modules = 0.25;
    // The smoothed point never trails the measured one by more than this.
    double max_lag_modules = 0.02;
    // Every frame without a lock runs the first scan's first pairs over its
    // edgel sets (search_plan.hpp's spread_first) and the next share of the
    // other parts' pieces (search_share), round after round; false: every
    // search on every frame without a lock, as for a photo on its own. For
    // a device that cannot search a whole frame between two camera frames
    // (docs/BENCHMARKS.md, "Detector speed in real time"); offline, where
    // every frame is looked at, it finds fewer, and a photo wants every
    // search.
    bool spread_search = false;
    // A share's pieces, in search_plan.hpp's kPieceCost units (ms at 640 x
    // 480 on the machine they were measured on).
    double search_budget = 2;
    // The time a frame's search may take on this device, in ms: when set,
    // each frame runs the first scan, the round's next step from where the
    // last frame stopped, and the steps after it while they fit in that time
    // (search_plan.hpp's SearchLimit), in place of shares of search_budget.
    // So a frame without the field costs about this much (or its first scan
    // and a step, where those alone take longer; see hold_first_scan), and
    // the round goes on at the device's own pace.
    double frame_ms = 0;
    // With frame_ms: the first scan held to a time too, first_scan_times
    // frame_ms, by default the whole time between two camera frames (as
    // frame_ms is kSpreadFrameShare of it). Its search of the part around
    // the aim runs whatever the time, its searches of the whole frame while
    // they fit, taken up on the next frame where they stopped, each next
    // step taken to cost as much as the dearest so far: a frame without the
    // field then keeps to about that time (the first scan alone costs up to
    // 4 ms at 640 x 480 on content dense with edges; on a device four times
    // slower, more than its half of a frame's time at 25 frames a second),
    // and drops fewer frames in real time (docs/BENCHMARKS.md, "the first
    // scan held to the frame's whole time": as many found on the tuning
    // set; held-out, 9 of 360 fewer at 1280 x 720 in real time and 13 of
    // 180 fewer held to 2 ms, where the whole frame's searches cost more).
    // Held to frame_ms itself (first_scan_times 1) it finds fewer. Not yet
    // the default.
    bool hold_first_scan = false;
    double first_scan_times = 1 / kSpreadFrameShare;
};

enum class TrackState {
    searching,  // no lock yet (or not for a long time): full detection
    locked,     // this frame verified a place
    lost,       // there was a lock recently, this frame verified none
};

const char* to_string(TrackState state);

struct TrackResult {
    TrackState state = TrackState::searching;
    Detection detection;                             // this frame's own result
    Eigen::Vector2d aim_field = Eigen::Vector2d::Zero();  // smoothed, valid when locked
    bool used_prior = false;                         // the lock came from the prediction
    int frames_since_lock = 0;                       // 0 when locked
};

class Tracker {
public:
    // The detector must outlive the tracker.
    explicit Tracker(const Detector& detector, TrackerOptions options = {});

    TrackResult update(const GreyView& image);
    TrackResult update(const GreyView& image, const Eigen::Vector2d& aim);
    void reset();

private:
    Detection spread_search(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                            bool use_prior);
    Detection timed_search(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                           bool use_prior);

    const Detector* detector_;
    TrackerOptions options_;
    bool has_prior_ = false;
    Eigen::Matrix3d last_image_to_field_ = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d motion_ = Eigen::Matrix3d::Identity();  // image motion per frame, A_{t-1}^-1 A_t
    bool has_motion_ = false;
    bool last_full_size_ = false;  // the last lock's map came from the frame at its own size
    Eigen::Vector2d last_raw_aim_ = Eigen::Vector2d::Zero();
    Eigen::Vector2d smoothed_ = Eigen::Vector2d::Zero();
    int frames_since_lock_ = 0;
    // The spread search: the round's next piece, the share that found the
    // last lock (no pieces: none yet). Held to frame_ms: the next piece's
    // steps already searched, the piece and step that found the last lock
    // (-1: none, or the first scan).
    int next_piece_ = 0;
    int finding_first_piece_ = 0;
    int finding_pieces_ = 0;
    int next_step_ = 0;
    // Held to frame_ms with hold_first_scan: the first scan's step on the
    // whole frame to take up (0: its first; -1: the part around the aim
    // alone, the round's frame).
    int first_scan_from_ = 0;
    int finding_first_step_ = 0;  // the first scan's step on the whole frame that found the last lock (0: none)
    int finding_piece_ = -1;
    int finding_step_ = 0;
};

}  // namespace umf
