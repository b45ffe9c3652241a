// Where each point of one camera frame lies in another of the same screen:
// the homography between two frames of a flat scene, found from their grey
// levels directly. A hand-held phone's frames of a faint pulse must be laid
// onto each other before they are demodulated together (pulse_search.hpp),
// and before the field is found the content is all there is to align on:
// it lies on the screen's plane with the field, so the homography that
// aligns the content aligns the field.
//
// The alignment is Gauss-Newton on the eight parameters of the homography
// (on request six, an affine change, at the coarsest level; inverse
// compositional: the gradients of `from` are taken once a level), coarse
// to fine over image pyramids, on the pixels of strongest gradient,
// with Huber weights so that what moves apart from the screen (a hand, the
// wall beside it) and the pulse's own change weigh little, and a grey-level
// offset estimated beside it (exposure and the pulse change the mean), and
// on request the exposure's gain (RegistrationOptions::fit_gain).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "shared/detect/image.hpp"

namespace umf {

// A frame at its full size and at halves of it down to a smallest width,
// built once and aligned against its neighbours before and after it.
class FramePyramid {
public:
    FramePyramid() = default;
    // Copies the frame; halves it while the half is at least `smallest_width`
    // pixels wide.
    FramePyramid(const GreyView& frame, int smallest_width = 80);

    int levels() const { return static_cast<int>(levels_.size()); }
    GreyView level(int i) const;
    // The level less its local mean (a box of kDetailRadius pixels of the
    // level each way), about grey 128: the content's edges without the
    // light's slow change over the frame. Made on the first call (only a
    // registration that the grey levels failed reads it); the view stays
    // valid as long as the pyramid.
    GreyView detail(int i) const;
    static constexpr int kDetailRadius = 4;
    int width() const { return levels_.empty() ? 0 : levels_[0].width; }
    int height() const { return levels_.empty() ? 0 : levels_[0].height; }

private:
    struct Level {
        std::vector<std::uint8_t> pixels;
        int width = 0, height = 0;
    };
    std::vector<Level> levels_;
    mutable std::vector<Level> details_;  // per level; empty until detail() asks
};

// A pyramid level's pixels against the frame's own, as FramePyramid halves
// (each pixel the mean of two by two): a level-l pixel's centre x is the
// frame's s x + (s - 1) / 2, s = 2^l.
class LevelMap {
public:
    explicit LevelMap(int level);
    double scale() const { return scale_; }
    // The level's pixels to the frame's, and back.
    const Eigen::Matrix3d& to_frame() const { return to_frame_; }
    const Eigen::Matrix3d& from_frame() const { return from_frame_; }
    Eigen::Vector2d to_frame(const Eigen::Vector2d& level_point) const;
    Eigen::Vector2d from_frame(const Eigen::Vector2d& frame_point) const;
    // A homography between two frames' own pixels, between their level's.
    Eigen::Matrix3d homography(const Eigen::Matrix3d& between_frames) const {
        return from_frame_ * between_frames * to_frame_;
    }

private:
    double scale_;
    Eigen::Matrix3d to_frame_, from_frame_;
};

struct RegistrationOptions {
    // The finest level aligned (0: full size, 1: half size); the homography
    // found at half size is within a few tenths of a full-size pixel.
    int finest_level = 1;
    int iterations = 15;   // at most, at each level
    int samples = 2500;    // pixels of strongest gradient aligned at each level
    // Done at a level once no corner of the frame moves more than this
    // (pixels of that level) in an iteration.
    double converged_px = 0.02;
    // Registered when at least `min_overlap` of the samples land inside the
    // other frame and the robust spread of the grey-level difference after
    // alignment is at most `max_residual` levels or at most `max_share` of
    // that between the frames as they lie. (Sharp content aligned exactly
    // still differs by many levels at its edges, sampled at other phases:
    // 8 at full size and 19 at half size on a simulated web page.)
    double max_residual = 8;
    double max_share = 0.7;
    double min_overlap = 0.5;
    // The grey levels' gain fitted beside their offset: once aligned with
    // the offset alone, and the finest level aligned again with the gain
    // where it differs from 1 by more than `least_gain`. Off by default: on
    // the tuning set's pulsing videos the offset alone (with its Huber
    // weights) registers as many frames under an exposure that drifts by 8 %,
    // and the gain cost 27 of 433 frames found where the exposure is steady
    // (umf_pulse_benchmark --frame-ms 0 [--exposure-drift 0.08] [--gain]).
    // For a camera whose exposure jumps by more (15 % in the test).
    bool fit_gain = false;
    double least_gain = 0.02;
    // The coarsest level aligned with an affine change of the guess alone
    // (six parameters), the levels after it with all eight: from one frame
    // to the next the view's perspective changes little, and with its two
    // parameters free at the coarsest level the lines of a document can
    // slide one line along. Off by default: a fast swing's perspective
    // changes by more (PulseSearchOptions::affine_retry uses it where the
    // whole homography fails).
    bool affine_coarse = false;
    // Aligned on each level less its local mean (FramePyramid::detail), not
    // on its grey levels: a lamp's glare on the screen or a vignette changes
    // the light smoothly over the frame, by far more than a pulse, and one
    // grey-level offset for the whole frame cannot follow it. Off by
    // default (PulseSearchOptions::detail_retry uses it where the grey
    // levels fail).
    bool detail = false;
};

struct FrameRegistration {
    // Takes a point of `from` (pixel centres at integer coordinates, as
    // everywhere in the detector) to the same point of the screen in `to`.
    Eigen::Matrix3d homography = Eigen::Matrix3d::Identity();
    double residual = 0;  // the robust spread of the grey-level difference, levels
    double unmoved_residual = 0;  // the same between the frames as they lie
    double guess_residual = 0;    // the same where the guess lays them
    double overlap = 0;   // the share of samples inside `to`
    double gain = 1;      // of `to`'s grey levels over `from`'s
    bool on_detail = false;  // aligned on the frames' detail (RegistrationOptions::detail)
    bool registered = false;
};

// `from` and `to` must be of the same size; `guess` (in the same terms as
// the result) is where the alignment starts: the last frame's motion, or
// the identity. Throws std::invalid_argument for frames of different sizes.
FrameRegistration register_frames(const FramePyramid& from, const FramePyramid& to,
                                  const Eigen::Matrix3d& guess = Eigen::Matrix3d::Identity(),
                                  const RegistrationOptions& options = {});

// `frame` resampled (bilinear) through `homography`, which takes its points
// to those of the output: out(x) = frame(homography^-1 x). Pixels that come
// from outside the frame take `outside`'s pixel at the same place. Into
// `out`, reused between calls; a view of it.
GreyView warp_frame(const GreyView& frame, const Eigen::Matrix3d& homography, const GreyView& outside,
                    std::vector<std::uint8_t>& out);

}  // namespace umf
