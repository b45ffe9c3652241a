// The detector: finds the field in a grey camera frame and the field point
// under the aim point (the image centre unless given). The pipeline, one
// stage per file:
//   1. edgels on sparse scanlines            (edgels.hpp)
//   2. two vanishing points                  (vanishing_points.hpp)
//   3. the grid lines of both families       (grid_lines.hpp)
//   4. grid homography from line crossings   (homography.hpp)
//   5. module values or edge signs           (classify.hpp)
//   6. window lookup and placement vote      (window_index.hpp, placement_vote.hpp)
//   7. the homography refitted to the field's own module edges (refine.hpp),
//      then checked: the whole view must read as the field at that place,
//      and so must the modules around the aim point (aim_check.hpp)
//   8. the aim point from a refit to the module edges around it
// The first scan looks at the part of the frame around the aim first (half
// its width and height, as a frame of its own), then at the whole frame.
// When the first scan finds nothing, the other parts of the search run in
// turn (search_plan.hpp, kPartOrder: the order that finds the tuning
// frames soonest for their cost): steps 1 to 8 on the frame at half size
// (image.hpp's half_size) and below, at double size around the aim
// (double_size), on denser and noisier scans, on the frame smoothed; and
// in place of steps 1 to 4 a lattice read from the spectrum of edge
// strength around the aim (lattice.hpp), for modules of 3-5 pixels, at the
// frame's size and smaller ones, for a faint field's larger modules. A
// video's frame may run only some of these (search_plan.hpp).
// A wrong place is worse than none: every stage may end in "not found".
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "shared/detect/aim_check.hpp"
#include "shared/detect/classify.hpp"
#include "shared/detect/edgels.hpp"
#include "shared/detect/field_likeness.hpp"
#include "shared/detect/grid_lines.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/lattice.hpp"
#include "shared/detect/module_centring.hpp"
#include "shared/detect/placement_vote.hpp"
#include "shared/detect/refine.hpp"
#include "shared/detect/search_cache.hpp"
#include "shared/detect/search_plan.hpp"
#include "shared/detect/stage_time.hpp"
#include "shared/detect/vanishing_points.hpp"
#include "shared/detect/window_index.hpp"

namespace umf {

struct DetectorOptions {
    EdgelOptions edgels;
    VanishingOptions vanishing;
    GridLineOptions grid;
    ClassifyOptions classify;
    VoteOptions vote;
    RefineOptions refine;
    AimCheckOptions aim;
    // The aim point is read from a refit to the module edges within this
    // many modules of it: one homography for the whole view is off by a
    // tenth of a module or more at the aim under a rolling shutter.
    double aim_refit_modules = 4;
    // A refit around the aim that fits less than this share of the edges it
    // found may have started about half a module off (module_centring.hpp):
    // it runs again from where the module centres read the field most
    // strongly, and that refit places the aim where it fits at least this
    // share and more edges than the first. On the tuning set, 8 % of found
    // frames fit less than 0.9; the four that ended more than half a module
    // off fitted 0.71-0.89, and 25-40 edges, where the second refit fitted
    // 50-52 edges, 0.93-1.0 of them.
    double aim_refit_min_share = 0.9;
    CentringOptions centring;
    // A place is confirmed on the modules within this many of the aim first
    // (0: the whole view at once), and on the whole view where they refuse it.
    int confirm_reach_modules = 8;
    // A grid found without a prior is read and voted on within this many
    // modules of the aim first (0: never), and as a whole where that does
    // not place the field.
    int vote_reach_modules = 8;
    bool refine_enabled = true;
    // Windows that must agree, and outvote any other placement, for a grid
    // the vote does not accept as a whole to go on to the refit and checks.
    int provisional_votes = 4;
    bool rescan = true;  // scans on the lines in between (down to 4 px apart) when a scan finds nothing
    // When a scan of a noisy image finds nothing, the scan again three pixels
    // wide, where an edge must stand this many deviations of the scanline's
    // noise above it (EdgelOptions::noise_deviations), and the scans in
    // between likewise.
    double noisy_edge_deviations = 3;
    // When nothing is found, the search again on the frame at half size (and
    // so on) while its shorter side keeps this many pixels; 0: never. A
    // smear or defocus spreads a module's edge over more pixels than the
    // edgels' two pixels a side take in, at a fine sensor most: at half
    // size the edge is twice as steep.
    int half_size_min_side = 240;
    // The search also on the frame at twice its size, if its longer side is
    // at most this many pixels; 0: never. Modules of 3-4 pixels leave the edgels' two pixels
    // a side and the 3 x 3 gradients reaching into the next module's edge;
    // at twice the size (cubic interpolation) they reach half as far.
    int double_size_max_side = 1024;
    // The part of the frame searched at double size, around the aim, as a
    // fraction of its width and height: at a half, as many pixels as the
    // frame itself, and at 3-4 pixels a module still some 80 x 60 modules.
    double double_size_part = 0.5;
    // At double size an edgel's gradient may stray this far from the
    // direction to its vanishing point (VanishingOptions::max_inlier_deg,
    // 15 elsewhere): the interpolated image rounds the corners of modules of
    // 3-4 pixels, and their edges' gradients turn by 20 degrees and more.
    double double_size_max_inlier_deg = 25;
    // The field's grid also as the lattice the spectrum of edge strength
    // around the aim shows (lattice.hpp): the modules of a far screen, 3-5
    // pixels, turn the edgels' gradients too far for steps 2-4.
    bool lattice_enabled = true;
    // The lattice also on the frame at half size, a quarter and so on, this
    // many sizes (0: only the frame's own), while the patch fits: a faint
    // field's modules of 10-40 pixels, whose edges are too weak for the
    // edgels' directions, span the lattice's 3-12 pixels at one of them,
    // and the spectrum gathers the evidence of every module in the patch.
    int lattice_sizes = 3;
    // The part of the frame around the aim that a plan's first scan searches
    // first (SearchPlan::near_aim_first), as a fraction of its width and
    // height; 0 or 1: never.
    double near_aim_part = 0.5;
    // A plan's first scan of the whole frame after the part around the aim
    // (SearchPlan::whole_frame_halved) made on the frame at half size where
    // that keeps this many pixels on its shorter side (a 1280 x 720
    // camera's frame; 0: never): a field filling that view has modules of
    // 10 pixels and more, as steep at half size, and the content's edges
    // are a quarter as many (tuning set at 1280 x 720, the first scan of the
    // whole frame alone: 272 of 280 frames with the field found against
    // 259, frames without it 1.4 / 3.5 ms median / p95 against 1.8 / 5.3).
    int whole_frame_half_min_side = 360;
    // The search at the frame's size and smaller ones also on the frame
    // smoothed (`smoothed` in image.hpp, a Gaussian of sigma 1.4 px). A screen's colour stripes under a scaler
    // that skips photosites fold into a hatch of 2-5 px, and a dim room's
    // noise does likewise at the pixel's scale: their edges outnumber a faint
    // field's and pull the grid directions to their own. The smoothing keeps
    // little of them and a module's edges whole, but blunts small modules.
    bool smoothed_search = true;
    // When a scan's field-like edgels (field_edgels.hpp) and all of them
    // find nothing, they are searched once more without the thin lines among
    // them, up to this many pixels wide (0: not): a spreadsheet's rules run
    // with the field's lines and outweigh a faint field's edges.
    double thin_line_px = 6;
    // Pairs of grid-line labellings (step 4) each search tries in a first
    // pass over every search; the rest follow in a second pass (0: all in
    // one). Of the searches that found the field on the tuning frames at
    // 640 x 480, nearly all did so within their first nine pairs; a search
    // that fails tries every pair, most often 15 to 27.
    int first_pass_pairs = 9;
    // A search that fails, where a grid under the aim read as a marker
    // field with at least this many windows read whole, yet no grid came
    // near a place of this field (field_likeness.hpp), saw another screen's
    // field (Detection::another_field). 0: never. The search is not cut
    // short there: a grid labelled wrongly on the paired screen's own field
    // reads the same way, and a later labelling finds the place (stopping
    // at the first such grid lost a tenth of the tuning set's frames and a
    // third of the held-out set's).
    int another_field_windows = 30;
    FieldLikenessOptions field_likeness;
    LatticeOptions lattice;
    double corner_tolerance_px = 1.5;  // robust grid homography
};

struct StageTimes {
    double edgels_ms = 0, vanishing_ms = 0, grid_ms = 0, classify_ms = 0, vote_ms = 0, refine_ms = 0, total_ms = 0;
};

struct Detection {
    bool found = false;
    Eigen::Matrix3d image_to_field = Eigen::Matrix3d::Identity();
    Eigen::Vector2d aim_image = Eigen::Vector2d::Zero();
    // (u, v) in modules, from the module edges around the aim: within a few
    // hundredths of a module of where image_to_field, fitted to the whole
    // view, takes the aim (image_to_field_through_aim joins the two).
    Eigen::Vector2d aim_field = Eigen::Vector2d::Zero();
    int windows = 0;          // windows that agreed on the place
    bool from_prior = false;  // confirmed near the predicted place rather than found anew
    double size_scale = 1;    // found on the frame at this many times its size (0.5: half size, 2: double)
    bool from_lattice = false;  // its grid came from the spectrum around the aim (lattice.hpp)
    bool from_smoothed = false;  // found on the frame smoothed (DetectorOptions::smoothed_search)
    bool from_near_aim = false;  // found on the part of the frame around the aim (SearchPlan::near_aim_first)
    int edges_fitted = 0;     // module edges the final homography was fitted to (0: grid lines only)
    double confidence = 0;    // fraction of the read modules or edges the place explains
    int places_checked = 0;   // candidate places that reached the final check (each costs evidence)
    int grids_read = 0;       // grids whose modules were read and voted on (step 5): most of a search's work
    StageTimes times;
    long pixels_visited = 0;
    std::string failure;      // the stage that ended the search, when not found
    // Windows read whole from the largest grid under the aim that read as a
    // field but as none of this field's places (0: none such).
    int another_field_windows = 0;
    // Not found, and the view shows another field where the aim is
    // (DetectorOptions::another_field_windows): another screen's.
    bool another_field = false;
};

// The view's image-to-field map shifted in the field to take the aim exactly
// to aim_field: for whoever reports one map and one point.
Eigen::Matrix3d image_to_field_through_aim(const Detection& detection);

// Where the field was: the image-to-field homography of a recent frame, and
// how far (modules) the place may have moved since. Lets the detector confirm
// a place near it on much less evidence than a search of the whole field.
struct DetectionPrior {
    Eigen::Matrix3d image_to_field = Eigen::Matrix3d::Identity();
    int radius_modules = 3;
};

class Detector {
public:
    // Throws std::invalid_argument for a field that is not 4-orientable.
    explicit Detector(const Field& field, DetectorOptions options = {});

    Detection detect(const GreyView& image) const;
    Detection detect(const GreyView& image, const Eigen::Vector2d& aim) const;
    Detection detect(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior) const;
    // Only the searches `plan` names (search_plan.hpp): a video's frame.
    Detection detect(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                     const SearchPlan& plan) const;
    // The plans in turn until one finds the field, then the second pass over
    // them all (full_search() is a photo's search).
    Detection detect(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                     std::span<const SearchPlan> plans) const;
    // The same held to `limit` (search_plan.hpp's SearchLimit), which says
    // where it stopped: a video's frame without a lock.
    Detection detect(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                     std::span<const SearchPlan> plans, SearchLimit& limit) const;
    // Colour frames are detected on their luma (image.hpp's to_luma).
    Detection detect(const ColourView& image) const;

    // Video: confirms the field near where it is predicted to be, without
    // searching for it. The module edges the prediction expects are searched
    // and fitted (they must lie within about 0.4 module of the prediction),
    // then the modules are read under the fit and must single out the
    // predicted placement among its neighbours. Much cheaper than detect()
    // and works on fainter fields; "not found" when the prediction was off.
    Detection follow(const GreyView& image, const Eigen::Vector2d& aim,
                     const Eigen::Matrix3d& predicted_image_to_field) const;

    const Field& field() const { return index_.field(); }

private:
    // The one failure that ends a search at once: a place was accepted, but
    // the aim maps to infinity under it. Compared by address.
    static const char kAimAtInfinity[];
    // The failure of a search that saw another screen's field.
    static const char kAnotherField[];
    // Which pairs of grid-line labellings a search tries (step 4). The first
    // pass tries the likeliest few of every search at every size and scan,
    // the second the rest, so that a field found by a later search at its
    // likeliest pair does not first pay for every unlikely pair of the
    // searches before it. `left` holds, per search in the order they run,
    // its labellings when the first pass left pairs of them to the second;
    // the second pass ends after the last such search.
    struct Pass {
        struct Labellings {
            std::vector<GridLineFamily> family[2];
        };
        SearchPlan plan;  // the part of the search running
        SearchCache cache;  // images and scans the parts share
        int first_pair = 0;
        int end_pair = 0;
        std::vector<Labellings> left;
        std::size_t end_of_left = 0;  // one past the last search with pairs left
        std::size_t search = 0;       // the searches run so far in this pass
        // What ended the first search over edgels: the failure a frame
        // reports, whichever plans its search was cut into.
        const char* first_search_failure = nullptr;
        // The lattice at the frame's own size ran (SearchPlan::lattice_first_if_small).
        bool lattice_searched = false;
        // The whole frame's first scan after the part around the aim is
        // being searched, with SearchPlan::whole_frame_field_like_alone.
        bool field_like_alone = false;
        // The time limit (null: none) and when the call began, the steps
        // run in the call over every plan (its average step), when the last
        // one began and the dearest of the others, the plan running and its
        // steps so far (SearchLimit), and whether the limit stopped the
        // search.
        SearchLimit* limit = nullptr;
        StageClock::time_point start{};
        int call_steps = 0;
        StageClock::time_point step_began{};
        double dearest_step_ms = 0;
        int plan_index = 0;
        int steps = 0;
        bool stopped = false;

        bool first() const { return first_pair == 0; }
        bool nothing_left() const { return stopped || (!first() && search >= end_of_left); }
        // Whether the time limit stops the search before the plan's next
        // step (and so before the images and scans made for it): whether
        // that step would end past it, taken to cost what the call's steps
        // have cost on average so far, or with SearchLimit's
        // as_dear_as_dearest as much as the dearest of them where more (the
        // same frame's content).
        bool out_of_time();
        // Counts the plan's next step: whether to run it (false: not
        // wanted on this frame, searched on an earlier one, or out of time).
        bool take_step(bool wanted = true);
    };
    // detect over the plans, held to `limit` when there is one.
    Detection detect_plans(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                           std::span<const SearchPlan> plans, SearchLimit* limit) const;
    // One pass over the plans in turn, until one finds the field: the
    // failure of the first search over edgels (else of the first plan), or
    // null when found.
    const char* search_plans(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                             std::span<const SearchPlan> plans, Pass& pass, Detection& out) const;
    // The parts of the search pass.plan names: steps 1 to 8 on the image at
    // its own size, then (when nothing is found) at half size and below,
    // then on a lattice around the aim, then at double size, then on the
    // image smoothed at its own size and below; the failure, or null when
    // found.
    const char* search_sizes(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                             Pass& pass, Detection& out) const;
    // Steps 1 to 8 on the image at its own size (the scans in `scans`), then
    // at half size, and so on while the image is large enough (the scans in
    // `smaller_scans` at each of those sizes; none: not resized).
    const char* search_smaller(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                               Pass& pass, Detection& out, unsigned scans = kEveryScan,
                               unsigned smaller_scans = kEveryScan) const;
    // Steps 1 to 8 on `part` of the image (its corner at `origin`) resized
    // by `scale`, 0.5 (and on down, as search_smaller) or 2; the detection
    // is taken back to the image's coordinates.
    const char* search_resized(const GreyView& part, double scale, const Eigen::Vector2d& origin,
                               const Eigen::Vector2d& aim, const DetectionPrior* prior, Pass& pass,
                               Detection& out, unsigned scans, unsigned smaller_scans) const;
    // Steps 1 to 8 on the image at its own size: the scans, each wider or
    // denser than the last, until one finds the field; `vanishing` is step
    // 2's options at this size (wider at double size); only the scans in
    // `scans` (SearchPlan::scans) are searched.
    const char* search_scans(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                             const VanishingOptions& vanishing, Pass& pass, Detection& out,
                             unsigned scans = kEveryScan) const;
    // The first scan and search_edgel_sets on the part of the image around
    // the aim (DetectorOptions::near_aim_part), its scanlines as far apart
    // as the whole image's; the detection is taken back to the image's
    // coordinates.
    const char* search_near_aim(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                const VanishingOptions& vanishing, Pass& pass, Detection& out) const;
    // SearchPlan::lattice_first_if_small: the lattice around the aim before
    // the grids of `edgels` are read, where they say the modules are small
    // and the lattice has not run in this pass. Counted as a step whether or
    // not it runs, so that a frame taking up the first scan where the last
    // one stopped counts the same steps. The failure when that ends the
    // search (null: found), nothing when the search goes on.
    std::optional<const char*> lattice_if_small(const GreyView& image, const Eigen::Vector2d& aim,
                                                const DetectionPrior* prior, const std::vector<Edgel>& edgels,
                                                Pass& pass, Detection& out) const;
    // search over a scan's field-like edgels alone, then, when that fails,
    // over all of them, then over those not on thin lines
    // (field_edgels.hpp; SearchPlan::edgel_sets names those searched). The
    // sets in `searched_sets` (searched before in this pass) are counted as
    // steps and not searched again; those searched are added to it.
    const char* search_edgel_sets(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                  const VanishingOptions& vanishing, const EdgelScan& scan, Pass& pass,
                                  Detection& out, unsigned& searched_sets) const;
    // Steps 2 to 8 on one scan's edgels; the failure, or null when found.
    const char* search(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                       const VanishingOptions& vanishing, const EdgelScan& scan, Pass& pass,
                       Detection& out) const;
    // Steps 2 and 3 on one scan's edgels: the labellings of both families'
    // grid lines, each with its first made; the failure, or null.
    const char* find_labellings(const GreyView& image, const VanishingOptions& vanishing, const EdgelScan& scan,
                                Detection& out, std::optional<GridLineLabellings> (&labellings)[2]) const;
    // Steps 5 to 8 on the lattices around the aim (lattice.hpp) in place of
    // steps 1 to 4; the failure, or null when found.
    const char* search_lattice(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                               Detection& out) const;
    // The same at half size and below (DetectorOptions::lattice_sizes): at
    // half size when bit 0 of `sizes` is set, a quarter with bit 1, and so on.
    const char* search_lattice_smaller(const GreyView& image, const Eigen::Vector2d& aim,
                                       const DetectionPrior* prior, Pass& pass, Detection& out,
                                       unsigned sizes) const;
    // Steps 5 to 8 on one grid (`grid_to_image`, rows x cols cells): its
    // modules read, the vote (near the prior first), the refit and checks,
    // the aim point; the failure, or null when found.
    const char* read_grid(const GreyView& image, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                          const Eigen::Matrix3d& grid_to_image, int rows, int cols, Detection& out) const;
    // Step 8: the view's image-to-field map, and the aim point in field
    // coordinates from the module edges around it (from `field_to_image`
    // alone where too few are found). False when the aim maps to infinity.
    bool place_aim(const GreyView& image, const Eigen::Matrix3d& field_to_image, const Eigen::Vector2d& aim,
                   Detection& out) const;
    // place_aim's refit within aim_refit_modules of `from` (field), started
    // from `field_to_image`: the aim in field coordinates and the refit, or
    // nothing where it found too few edges or moved the aim more than the
    // edges' search reaches.
    struct AimRefit {
        Eigen::Vector2d aim_field;
        int edges_fitted = 0;
        int edges_found = 0;
    };
    std::optional<AimRefit> refit_at_aim(const GreyView& image, const Eigen::Matrix3d& field_to_image,
                                         const Eigen::Vector2d& from, const Eigen::Vector2d& aim, Detection& out) const;
    // Steps 5-7 for the modules of grid `g2i` within
    // DetectorOptions::vote_reach_modules of the aim: whether their vote
    // placed the field and the place was confirmed (its homography and edges
    // fitted then in `field_to_image` and `edges_fitted`).
    bool place_near_aim(const GreyView& image, const Eigen::Vector2d& aim, const Eigen::Matrix3d& g2i, int rows, int cols,
                        Detection& out, Eigen::Matrix3d& field_to_image, int& edges_fitted) const;
    // Step 8 for a confirmed place: the aim point, and the detection found.
    const char* finish_place(const GreyView& image, const Eigen::Vector2d& aim, const Eigen::Matrix3d& field_to_image,
                             int edges_fitted, bool from_prior, Detection& out) const;
    // Step 7 for one vote on the grid `g2i`: the refit around the voting
    // windows and the final checks (of the voted homography too, when the
    // refit's is refused). The reason for refusing, or null; the homography
    // and the edges it was fitted to either way.
    const char* place_from_vote(const GreyView& image, const Eigen::Vector2d& aim, const Eigen::Matrix3d& g2i,
                                const VoteResult& vote, Detection& out, Eigen::Matrix3d& field_to_image,
                                int& edges_fitted) const;
    bool grid_homography(const GridLineFamily& rows_family, const GridLineFamily& cols_family, const GreyView& image,
                         Eigen::Matrix3d& grid_to_image, int& rows, int& cols) const;

    // Reads the field's visible modules under `field_to_image` and checks that
    // they single out exactly that placement, by `extra_bits` more evidence
    // than a first candidate needs, and that the modules around the aim do
    // too (aim_check.hpp); records windows and confidence. The reason for
    // refusing, or null.
    const char* confirm_place(const GreyView& image, const Eigen::Matrix3d& field_to_image, const Eigen::Vector2d& aim,
                             Detection& out, double extra_bits = 0) const;
    // Modules from row r0 and column c0 up to, not including, r1 and c1.
    struct ModuleBox {
        int r0, c0, r1, c1;
    };
    // The modules within `reach` of the one under `at` (column x, row y),
    // inside `within`; nothing for no reach (or one past a million) or a
    // point farther off `within` than the reach (so nothing overflows an int).
    static std::optional<ModuleBox> box_around(const Eigen::Vector2d& at, int reach, const ModuleBox& within);
    // confirm_place's check over one box of the field's modules.
    const char* confirm_in(const GreyView& image, const Eigen::Matrix3d& field_to_image, const ModuleBox& box,
                           const Eigen::Vector2d& aim_field, Detection& out, double extra_bits) const;

    WindowIndex index_;
    ModuleEdges edges_;  // the field's, for every refit
    std::vector<double> brightness_;  // module_brightness of the field's values
    DetectorOptions options_;
};

}  // namespace umf
