// A field too faint for any one frame, found in the last frames together:
// each frame is registered onto the one before it as it comes
// (frame_registration.hpp: the content is on the screen's plane with the
// field, so what aligns the content aligns the field), the frames kept are
// laid onto the newest and demodulated (pulse_demodulator.hpp) against the
// pulse's course: where the pulse's shape is known (the welcome's period and
// waveform), that shape at the rate and phase that explain most of the
// frames' variation over time, otherwise the frames' leading course
// (pulse_course.hpp); the detector reads the demodulated image, in the newest frame's
// place. A frame that cannot be registered onto the one before it is set
// aside; where the next cannot be laid across it either (a cut, a view
// turned away), the frames kept start over.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/frame_registration.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/pulse_course.hpp"
#include "shared/detect/pulse_demodulator.hpp"
#include "shared/detect/search_plan.hpp"

namespace umf {

struct PulseShape {
    // The opacity over one period (phase 0..1, opacity in any scale).
    std::function<double(double phase)> waveform;
    double period_s = 0;
    // The opacities the pulse runs between, as announced (both 0: not
    // known). Known, the content is taken out of the demodulated image
    // (PulseDemodulator::full_opacity_image).
    double opacity_min = 0, opacity_max = 0;
};

struct PulseSearchOptions {
    int frames = 24;      // kept, the oldest dropped first
    int min_frames = 8;   // before the first search
    // Of the frames' variation over time, the share the pulse's course must
    // explain before the detector is asked (noise alone: about 1 / frames).
    double min_share = 0.2;
    std::optional<PulseShape> shape;
    // The frame rates tried when fitting the shape: image files carry none.
    std::vector<double> frame_rates = {24, 25, 30, 50, 60};
    // How each frame is registered onto the one before it.
    RegistrationOptions registration;
    // A registration whose motion differs from the last frame's by more
    // than this share of the frame's width at a corner is taken for none:
    // a hand's motion changes little from one frame to the next, while a
    // content with little but the faint field to align on (a blank page)
    // can be aligned a few modules off.
    double max_motion_change = 0.03;
    // Unless the frames show it: the registration from the motion guessed
    // leaves at most this share of the grey levels' spread that the guess
    // does (FrameRegistration::guess_residual; 0: never), departs from it by
    // at most kOutOfStepReach times the change allowed, and comes to the
    // same place from where the view stands (kSameAlignmentPx). A hand that
    // speeds up leaves its last motion behind: on the tuning set swung twice
    // as fast the check refused alignments within a pixel of the true motion
    // and the places carried through them were lost (umf_pulse_benchmark
    // --swing-speed 2 --out-of-step-share 0: 529 / 1 right / wrong, 622 / 1
    // at 0.5). On a blank page where an alignment ends hangs on where it
    // began: without the last two tests 6 of its frames were placed wrong
    // at that swing, with them 1, through an alignment in step (0 before).
    double out_of_step_share = 0.5;
    // A frame not registered (or refused by the motion check) is aligned
    // again with the coarsest level an affine change
    // (RegistrationOptions::affine_coarse): the tuning set's document slid
    // its lines one line along at a frame and lost every frame after it;
    // affine in every registration, the photo swung twice as fast was left
    // misaligned instead (27 frames right -> 3, and 24 wrong).
    bool affine_retry = true;
    // A frame still not registered is aligned again on the frames' detail
    // (RegistrationOptions::detail). The frames so aligned are kept, and a
    // place is carried through them only while the aim it was found at has come
    // at most detail_carry_modules over the field since the place was last
    // found or confirmed: content the grey levels could not align (a tiled
    // board's repeats, a glare) may be aligned a little off, frame after
    // frame, and the error grows with the way come (on the held-out tiled
    // board a place carried 40 frames through one such registration drifted
    // 0.02 module a frame). 0: not carried through one at all. Chosen on
    // the tuning set (umf_pulse_benchmark --detail-carry-modules X): 0 ->
    // 2 took its dark code 78 -> 109 frames right and its photo 118 -> 131,
    // none wrong; 1 gave 100 and 124, 5 the same as 2.
    bool detail_retry = true;
    double detail_carry_modules = 2;
    // A search that found nothing is not tried again until this many more
    // frames are kept (one that found the field is tried on every frame).
    int search_every = 4;
    // Once found, the field is carried from frame to frame through their
    // registration (the screen moves in the view as its content does), for
    // at most this many frames without a search that finds it again (or
    // confirms it: follow_carried). Each registration is a little off, and
    // the errors add up: on the tuning set's videos on a second seed
    // (umf_pulse_benchmark --seed 2 --log), places carried 18-32 frames
    // were 0.5-0.8 module off in 25 frames and within half a module in 5;
    // on the first seed and with either optics option, no place carried
    // more than 17 frames was right or wrong (60 was chosen when fewer
    // places were confirmed by a follow).
    int carry_frames = 17;
    // A place carried is looked for where it is said to be in each
    // demodulated image (Detector::follow) before the image is searched.
    bool follow_carried = true;
    // A follow reads the module edges near the aim, and its map can be far
    // off away from them: on the tuning web page swung twice as fast, one
    // follow's map put the points a tenth of the frame's width from the aim
    // 0.9 module from where the carried map put them, and the place carried
    // on from it drifted 2.3 modules (19 frames wrong). Where the two maps,
    // moved to agree at the aim, differ there by more than this (modules),
    // the carried map's shape is kept through the follow's place: 19 wrong
    // -> 3 at that swing, the tuning set at its own speed unchanged
    // (umf_pulse_benchmark --swing-speed 2).
    double max_follow_shape_change = 0.5;
    // Each frame laid onto the newest scaled to the newest's exposure before
    // the pulse is demodulated (the median ratio of their grey levels): a
    // phone's auto-exposure changes the content's levels by more than a faint
    // pulse changes the field's, and the frames' main course over time is
    // then the exposure's. A pure gain, as exposure is; on a blank page the
    // pulse is a change of contrast about the page's grey, which it keeps.
    bool level_exposure = true;
    // Where the pulse's range is announced (PulseShape::opacity_min, max),
    // the field alone is looked for too, after the slope image and its
    // inverse (PulseSearch::field_alone_images): on the tuning set's web page the
    // first right frame came at 11, not 19, and 8 more right (umf_pulse_benchmark
    // --no-field-alone).
    bool field_alone = true;
    // Where those hold no field, the slope with the content's leakage taken
    // out (PulseDemodulator::content_free_field_image), in tiles of this
    // share of the frame's width; 0 leaves it out. Over a moving view the
    // content's edges stay in the slope (tests/detect/content_leakage_scenes_test.cpp).
    double content_free_tile = 0.375;
    // What the detector runs there: the demodulated image's plans and,
    // first, the lattice at half size (search_plan.hpp's part 3), which
    // reads the modules the content's edges left in a tile's corners.
    std::vector<SearchPlan> content_free_plans = {spread_first(), search_part(3), search_part(2), search_part(5)};
    // What the detector runs on a demodulated image: the first scan of a
    // video's frame, then the scan three pixels across and the image
    // smoothed (search_plan.hpp's parts 2 and 5): the demodulated image's
    // noise is a frame's over the pulse's small spread, tens of grey levels
    // from pixel to pixel, more from fewer frames. Its field is sharp and at
    // the content's contrast, or not there at all; the other fallbacks would
    // cost an image without it some 50 ms each time.
    std::vector<SearchPlan> plans = {spread_first(), search_part(2), search_part(5)};
    // A place carried is first followed in the frames demodulated at this
    // level of their pyramid (0: not; 1: half size, a quarter of the pixels
    // laid onto the newest, each the mean of four); only where it is not
    // confirmed there are they demodulated at their own size, followed and
    // searched. On the tuning set's four runs (umf_pulse_benchmark
    // --demodulation-level 0|1) an update's median fell 10-55 % for the same
    // counts (3004 / 10 right / wrong against 3006 / 10); searches at half
    // size too lost first locks (the photo's 7 -> 19).
    int demodulation_level = 1;
    // Each place the search gives (found, followed or carried) checked in
    // the newest frame alone (field_shift.hpp): the demodulated image shows
    // the field where the older frames, laid onto the newest, put it, and
    // a registration a pixel or two off puts it there, not where the newest
    // frame's own field is. Refused where that frame's field lies clearly
    // elsewhere: the best shift at least elsewhere_modules away, its
    // evidence at least elsewhere_t and elsewhere_over_content times what
    // the content alone gives (FieldShift::content_t), and the place's under
    // place_share of it. Chosen on the tuning set's videos on two seeds and
    // with both optics options (umf_pulse_benchmark --no-newest-check
    // --log): of the 19 frames placed wrong by a place carried at most 17
    // frames, 12 refused, and one right frame (0.43 module off) refused; a
    // best shift's evidence of 20-26 came from a photo's content alone.
    bool check_newest = true;
    double elsewhere_modules = 0.4;
    double elsewhere_t = 30;
    double elsewhere_over_content = 3;
    double place_share = 0.7;
};

struct PulseSearchResult {
    Detection detection;  // in the newest frame
    int frames = 0;       // kept when searching
    double share = 0;     // of their variation explained by the course
    bool fitted = false;  // the course is PulseSearchOptions::shape's
    // The course demodulated against, one value a frame kept, oldest first,
    // from -1 to 1 (empty where no pulse was found).
    std::vector<double> course;
};

class PulseSearch {
public:
    explicit PulseSearch(PulseSearchOptions options = {});

    // Copies the frame and registers it onto the last; one of another size
    // than those kept starts over. One that cannot be registered is set
    // aside: the next frame is laid onto the frames kept across it (a frame
    // smeared by the hand, or one whose alignment left too much unexplained),
    // and only where that fails too do the frames kept start over from it.
    // `time_s`: when the frame was taken, seconds on any clock; without it
    // the frames are taken to come at one of options.frame_rates.
    void add(const GreyView& frame, std::optional<double> time_s = std::nullopt);
    void clear();
    // The frames the newest lies among: 1 while it is set aside.
    int frames() const { return stray_ ? 1 : static_cast<int>(kept_.size()); }
    // The homography taking the last frame but one to the last: how the
    // screen moved in the view; empty when the last frame started over or
    // was set aside.
    std::optional<Eigen::Matrix3d> motion() const { return stray_ ? std::nullopt : motion_; }
    // How many frames could not be registered onto the one before them.
    int registration_losses() const { return unregistered_; }
    // How the last frame was laid onto the one before it (not registered:
    // the first frame, or one that started over or was set aside), and how
    // many frames back that one is (2 across a frame set aside).
    const FrameRegistration& last_registration() const { return last_registration_; }
    int last_registration_span() const { return last_span_; }

    // Whether a search is worth its cost now: enough frames kept, and
    // search_every more since a search that found nothing.
    bool due() const;
    // The field in the frames kept, or a detection that says why not.
    PulseSearchResult search(const Detector& detector, const Eigen::Vector2d& aim);
    // The place last found (by a search, or found_elsewhere) carried to the
    // newest frame through the registration of each frame since (from_prior
    // set); empty when nothing has been found, a frame since could not be
    // registered, or it was found more than carry_frames frames ago.
    std::optional<Detection> carried(const Eigen::Vector2d& aim) const;
    // Whether the newest frame's own field does not lie clearly elsewhere
    // than `place` puts it (PulseSearchOptions::check_newest).
    bool holds_in_newest(const Detection& place, const Field& field) const;
    // A place found in the newest frame some other way (a tracker's lock on
    // it alone): carried from here on in place of the last search's, which
    // has been carried further.
    void found_elsewhere(const Detection& found);
    // Frames since the place carried was found or confirmed, and how far
    // (modules) the aim has come over the field since: empty when none is.
    struct Carry {
        int frames = 0;
        double travel = 0;
    };
    std::optional<Carry> carry(const Eigen::Vector2d& aim) const;

private:
    struct Kept {
        FramePyramid pyramid;
        Eigen::Matrix3d to_newest;  // its points to the newest frame's
        std::optional<double> time_s;
        long number = 0;  // of frames added before it: a frame set aside leaves a gap
    };
    std::vector<double> fit_shape(const PulseCourse& course) const;
    std::vector<GreyView> field_alone_images(PulseDemodulator& demodulator, bool fitted);
    std::array<GreyView, 2> content_free_images(PulseDemodulator& demodulator);
    // The kept frames laid onto the newest at pyramid level `level` and
    // demodulated into `demodulator`; false where no pulse is in them.
    bool demodulate(int level, PulseDemodulator& demodulator, PulseSearchResult& out);
    // The field looked for in the demodulated images; whether a follow of
    // the place carried found it.
    bool look(const Detector& detector, const Eigen::Vector2d& aim, int level, PulseDemodulator& demodulator,
              PulseSearchResult& out, bool follow_only);
    void keep_found(const Detection& found);
    // Whether the aim has come at most detail_carry_modules over the field
    // since the place carried was found.
    bool near_found() const;

    PulseSearchOptions options_;
    int width_ = 0, height_ = 0;
    int added_since_search_ = 0;
    int unregistered_ = 0;
    bool last_found_ = false;
    std::deque<Kept> kept_;
    std::optional<Kept> stray_;  // the newest, not registered onto kept_'s newest
    bool stray_in_step_ = false; // its alignment refused but within the hand's motion
    long added_ = 0;             // frames added since the start
    // The frame's registration onto the last kept one (kept_ not empty),
    // `gap` frames on from it.
    FrameRegistration register_next(const FramePyramid& next, int gap) const;
    // The frame set aside starts the frames kept over.
    void start_over_from_stray();
    // Whether `motion` keeps within max_motion_change of `guess`, `gap`
    // frames on (the hand has had as many frames to change it).
    bool in_step(const Eigen::Matrix3d& motion, const Eigen::Matrix3d& guess, int gap) const;
    // Guesses closer than this at every corner are taken for one.
    static constexpr double kSameGuessPx = 0.5;
    // Two alignments of a frame from different starts that put every corner
    // within this of each other are taken for one.
    static constexpr double kSameAlignmentPx = 1.5;
    // How many times max_motion_change a registration the frames show may
    // depart from the motion guessed (out_of_step_share).
    static constexpr int kOutOfStepReach = 3;
    // Where a follow's map is compared with the carried one: this share of
    // the frame's width around the aim (max_follow_shape_change).
    static constexpr double kShapeReach = 0.1;

    std::optional<Eigen::Matrix3d> motion_;          // the last frame's, the next frame's first guess
    std::optional<Eigen::Matrix3d> earlier_motion_;  // the one before it
    FrameRegistration last_registration_;
    int last_span_ = 1;
    std::optional<Detection> found_;  // the last search's, carried to the newest frame
    int carried_for_ = 0;             // frames since it was found
    bool through_detail_ = false;     // one of them registered on the frames' detail
    std::vector<std::uint8_t> alone_pixels_[2];  // field_alone_images', reused
    std::vector<std::uint8_t> content_free_pixels_[2];  // the content-free slope and its inverse, reused
    std::vector<std::vector<std::uint8_t>> warped_;  // the kept frames laid onto the newest, reused
};

}  // namespace umf
