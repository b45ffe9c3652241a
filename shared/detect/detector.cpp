// Steps 5 to 8 of detection, from a candidate grid to a confirmed place, and
// the video path (follow). The search that finds candidate grids is in
// detector_search.cpp.
#include "shared/detect/detector.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "shared/detect/aim_check.hpp"
#include "shared/detect/field_likeness.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/stage_time.hpp"

namespace umf {

namespace {

// Grid point -> field point of a placement, as a matrix.
Eigen::Matrix3d placement_matrix(const GridPlacement& p) {
    double u0, v0, ux, vx, uy, vy;
    p.field_point(0, 0, u0, v0);
    p.field_point(1, 0, ux, vx);
    p.field_point(0, 1, uy, vy);
    Eigen::Matrix3d a;
    a << ux - u0, uy - u0, u0, vx - v0, vy - v0, v0, 0, 0, 1;
    return a;
}

// The placement a prior predicts for a grid: the turn from where the grid's
// x axis points in the field, the offsets from where the grid's centre lands.
std::optional<GridPlacement> predict_placement(const Eigen::Matrix3d& image_to_field, const Eigen::Matrix3d& g2i,
                                               int rows, int cols) {
    const Eigen::Matrix3d m = image_to_field * g2i;
    const Point2 c(cols / 2.0, rows / 2.0);
    auto p0 = apply_homography(m, c), px = apply_homography(m, c + Point2(1, 0));
    if (!p0 || !px) return std::nullopt;
    const Point2 d = *px - *p0;
    GridPlacement p;
    // x axis to +u, -v, -u, +v for quarter turns 0..3 (GridPlacement::field_point).
    if (std::abs(d.x()) >= std::abs(d.y()))
        p.quarter_turns = d.x() > 0 ? 0 : 2;
    else
        p.quarter_turns = d.y() < 0 ? 1 : 3;
    double u0, v0;
    p.field_point(c.x(), c.y(), u0, v0);
    p.col_offset = static_cast<int>(std::lround(p0->x() - u0));
    p.row_offset = static_cast<int>(std::lround(p0->y() - v0));
    return p;
}

// The aim lies on the grid (grid point (x, y) with x in [0, cols], y in [0, rows]).
bool covers(const Eigen::Matrix3d& grid_to_image, int rows, int cols, const Eigen::Vector2d& aim) {
    const auto g = apply_homography(grid_to_image.inverse(), Point2(aim.x(), aim.y()));
    return g && g->x() >= 0 && g->y() >= 0 && g->x() <= cols && g->y() <= rows;
}

}  // namespace

const char Detector::kAimAtInfinity[] = "aim point at infinity";
const char Detector::kAnotherField[] = "another field";

Detector::Detector(const Field& field, DetectorOptions options)
    : index_(field),
      edges_(index_.field()),
      brightness_(module_brightness(index_.field())),
      options_(std::move(options)) {}

Detection Detector::detect(const GreyView& image) const {
    return detect(image, Eigen::Vector2d(image.width / 2.0, image.height / 2.0));
}

Detection Detector::detect(const GreyView& im, const Eigen::Vector2d& aim) const { return detect(im, aim, nullptr); }

Detection Detector::detect(const ColourView& image) const {
    if (auto problem = describe_invalid(image); !problem.empty()) {
        Detection out;
        out.failure = "invalid image: " + problem;
        return out;
    }
    std::vector<std::uint8_t> luma;
    return detect(to_luma(image, luma));
}

const char* Detector::read_grid(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                const Eigen::Matrix3d& g2i, int rows, int cols, Detection& out) const {
    ++out.grids_read;
    Eigen::Matrix3d field_to_image;
    int edges_fitted = 0;
    // Without a prior, the modules around the aim first: a grid whose vote
    // they carry is placed without reading the rest of it.
    if (!prior && place_near_aim(im, aim, g2i, rows, cols, out, field_to_image, edges_fitted))
        return finish_place(im, aim, field_to_image, edges_fitted, false, out);
    // Step 5. Module values or edge signs.
    auto t = StageClock::now();
    const Field& f = index_.field();
    const ModuleGrid grid = classify_modules(im, g2i, rows, cols, f.colors, f.key == WindowKey::edges,
                                             options_.classify, out.pixels_visited);
    out.times.classify_ms += ms_since(t);

    // Step 6. Window lookup and the placement vote: near the predicted place
    // first, when there is a prior; the whole field's vote when that finds
    // nothing or its place is refused.
    t = StageClock::now();
    VoteResult near;
    if (prior) {
        if (auto predicted = predict_placement(prior->image_to_field, g2i, rows, cols))
            near = vote_near(grid, index_, *predicted, prior->radius_modules, options_.vote);
    }
    out.times.vote_ms += ms_since(t);
    const char* refused = near.found ? place_from_vote(im, aim, g2i, near, out, field_to_image, edges_fitted) : nullptr;
    const bool near_prior = near.found && !refused;
    t = StageClock::now();
    if (near_prior) {
        out.windows = near.votes;
        out.confidence = near.agreement;
    } else {
        const VoteResult vote = vote_placement(grid, index_, options_.vote);
        out.times.vote_ms += ms_since(t);
        // Report the accepted vote, or else the strongest one seen.
        if (vote.found || vote.votes > out.windows) {
            out.windows = vote.votes;
            out.confidence = vote.agreement;
        }
        // A grid labelled wrongly in part (a text line taken for a grid
        // line) still has windows that agree where it is right: the refit
        // grows out from them, and the checks judge it. A place refused near
        // the prior is not checked again.
        const bool weak = !vote.found && (vote.votes < options_.provisional_votes || vote.votes <= vote.runner_up);
        // The cheap tests first: most weak grids read too few windows.
        if (weak && options_.another_field_windows > 0 && vote.windows_read >= options_.another_field_windows &&
            covers(g2i, rows, cols, aim)) {
            const int foreign = foreign_field_windows(grid, vote, options_.field_likeness);
            if (foreign >= options_.another_field_windows)
                out.another_field_windows = std::max(out.another_field_windows, foreign);
        }
        if (weak || (near.found && near.placement == vote.placement)) return refused ? refused : "no agreeing windows";
        refused = place_from_vote(im, aim, g2i, vote, out, field_to_image, edges_fitted);
    }
    if (refused) return refused;
    return finish_place(im, aim, field_to_image, edges_fitted, near_prior, out);
}

bool Detector::place_near_aim(const GreyView& im, const Eigen::Vector2d& aim, const Eigen::Matrix3d& g2i, int rows,
                              int cols, Detection& out, Eigen::Matrix3d& field_to_image, int& edges_fitted) const {
    const auto at = apply_homography(g2i.inverse(), Point2(aim.x(), aim.y()));
    const auto near = at ? box_around(*at, options_.vote_reach_modules, {0, 0, rows, cols}) : std::nullopt;
    if (!near) return false;
    // Only where it leaves out much of the grid, and holds windows enough.
    const int side = index_.codec().window(), near_rows = near->r1 - near->r0, near_cols = near->c1 - near->c0;
    if (near_rows < 2 * side || near_cols < 2 * side || 2 * near_rows * near_cols > rows * cols) return false;
    auto t = StageClock::now();
    Eigen::Matrix3d shift;
    shift << 1, 0, near->c0, 0, 1, near->r0, 0, 0, 1;
    const Eigen::Matrix3d near_g2i = g2i * shift;
    const Field& f = index_.field();
    const ModuleGrid grid = classify_modules(im, near_g2i, near_rows, near_cols, f.colors, f.key == WindowKey::edges,
                                             options_.classify, out.pixels_visited);
    out.times.classify_ms += ms_since(t);
    t = StageClock::now();
    const VoteResult vote = vote_placement(grid, index_, options_.vote);
    out.times.vote_ms += ms_since(t);
    if (!vote.found) return false;
    out.windows = vote.votes;
    out.confidence = vote.agreement;
    return place_from_vote(im, aim, near_g2i, vote, out, field_to_image, edges_fitted) == nullptr;
}

const char* Detector::finish_place(const GreyView& im, const Eigen::Vector2d& aim, const Eigen::Matrix3d& field_to_image,
                                   int edges_fitted, bool from_prior, Detection& out) const {
    auto t = StageClock::now();
    out.edges_fitted = edges_fitted;
    const bool placed = place_aim(im, field_to_image, aim, out);
    out.times.refine_ms += ms_since(t);
    if (!placed) return kAimAtInfinity;
    out.from_prior = from_prior;
    out.found = true;
    return nullptr;
}

const char* Detector::place_from_vote(const GreyView& im, const Eigen::Vector2d& aim, const Eigen::Matrix3d& g2i,
                                      const VoteResult& vote, Detection& out, Eigen::Matrix3d& field_to_image,
                                      int& edges_fitted) const {
    auto t = StageClock::now();
    const Eigen::Matrix3d voted_f2i = g2i * placement_matrix(vote.placement).inverse();
    field_to_image = voted_f2i;
    edges_fitted = 0;
    // Step 7. Module edges around the voting windows, then outwards.
    if (options_.refine_enabled) {
        double su, sv;
        vote.placement.field_point(vote.centre_x, vote.centre_y, su, sv);
        const Refinement r =
            refine_homography(im, index_.field(), edges_, field_to_image, Point2(su, sv), options_.refine, out.pixels_visited);
        out.times.refine_ms += ms_since(t);
        if (r.refined) {
            field_to_image = r.field_to_image;
            edges_fitted = r.edges_fitted;
        }
    }
    // The final homography reaches beyond the windows that voted: the
    // modules it predicts over the whole view must read as the field, and
    // those around the aim must single out the place. Each candidate checked
    // is one more chance for a wrong place to pass: the n-th needs log2(n)
    // bits more than the first. A refit that strayed (pulled by content far
    // from the windows) leaves the voted homography as a candidate of its own.
    auto check = [&](const Eigen::Matrix3d& candidate) {
        ++out.places_checked;
        return confirm_place(im, candidate, aim, out, std::log2(static_cast<double>(out.places_checked)));
    };
    const char* refused = check(field_to_image);
    if (refused && edges_fitted > 0) {
        field_to_image = voted_f2i;
        edges_fitted = 0;
        refused = check(field_to_image);
    }
    return refused;
}

const char* Detector::confirm_place(const GreyView& im, const Eigen::Matrix3d& field_to_image, const Eigen::Vector2d& aim,
                                    Detection& out, double extra_bits) const {
    // The field's visible box: its modules under the homography.
    auto t = StageClock::now();
    const Field& f = index_.field();
    const Eigen::Matrix3d i2f = field_to_image.inverse();
    double u0 = f.width, v0 = f.height, u1 = 0, v1 = 0;
    const Eigen::Vector3d a = i2f * Eigen::Vector3d(aim.x(), aim.y(), 1.0);
    const double front = a.z();  // sign of points on the screen
    for (const Point2& corner : {Point2(0, 0), Point2(im.width, 0), Point2(0, im.height), Point2(im.width, im.height)}) {
        auto q = apply_homography(i2f, corner);
        if (!q || (i2f * Eigen::Vector3d(corner.x(), corner.y(), 1.0)).z() * front <= 0) {
            u0 = v0 = 0, u1 = f.width, v1 = f.height;
            break;
        }
        u0 = std::min(u0, q->x()), u1 = std::max(u1, q->x());
        v0 = std::min(v0, q->y()), v1 = std::max(v1, q->y());
    }
    const ModuleBox visible{std::max(0, static_cast<int>(std::floor(v0))), std::max(0, static_cast<int>(std::floor(u0))),
                            std::min(f.height, static_cast<int>(std::ceil(v1))),
                            std::min(f.width, static_cast<int>(std::ceil(u1)))};
    out.times.classify_ms += ms_since(t);
    // The modules around the aim first: where they single out the place, the
    // rest of the view adds nothing the aim depends on, and reading them is
    // most of the check's cost. Refused there, the whole view decides.
    const Eigen::Vector2d at = a.hnormalized();
    if (const auto near = box_around(at, options_.confirm_reach_modules, visible)) {
        const bool smaller = near->r0 > visible.r0 || near->c0 > visible.c0 || near->r1 < visible.r1 || near->c1 < visible.c1;
        if (smaller && confirm_in(im, field_to_image, *near, at, out, extra_bits) == nullptr) return nullptr;
    }
    return confirm_in(im, field_to_image, visible, at, out, extra_bits);
}

std::optional<Detector::ModuleBox> Detector::box_around(const Eigen::Vector2d& at, int reach, const ModuleBox& within) {
    // The comparisons also refuse a point at infinity or NaN.
    if (reach <= 0 || reach > (1 << 20) || !(at.x() > within.c0 - reach && at.x() < within.c1 + reach &&
                                             at.y() > within.r0 - reach && at.y() < within.r1 + reach))
        return std::nullopt;
    const int r = static_cast<int>(std::floor(at.y())), c = static_cast<int>(std::floor(at.x()));
    return ModuleBox{std::max(within.r0, r - reach), std::max(within.c0, c - reach), std::min(within.r1, r + reach + 1),
                     std::min(within.c1, c + reach + 1)};
}

const char* Detector::confirm_in(const GreyView& im, const Eigen::Matrix3d& field_to_image, const ModuleBox& box,
                                 const Eigen::Vector2d& aim_field, Detection& out, double extra_bits) const {
    // The grid is the field itself, so the expected placement is a plain
    // offset, and it must beat its neighbours one module away.
    if (box.c1 - box.c0 < 2 || box.r1 - box.r0 < 2) return "place not confirmed";
    auto t = StageClock::now();
    const Field& f = index_.field();
    Eigen::Matrix3d shift;
    shift << 1, 0, box.c0, 0, 1, box.r0, 0, 0, 1;
    const ModuleGrid grid = classify_modules(im, field_to_image * shift, box.r1 - box.r0, box.c1 - box.c0, f.colors,
                                             f.key == WindowKey::edges, options_.classify, out.pixels_visited);
    out.times.classify_ms += ms_since(t);
    VoteOptions vote_options = options_.vote;
    vote_options.min_evidence_bits += extra_bits;
    VoteResult vote = vote_near(grid, index_, GridPlacement{0, box.r0, box.c0}, 1, vote_options);
    out.times.vote_ms += ms_since(t);
    out.windows = vote.votes;
    out.confidence = vote.agreement;
    if (!vote.found || vote.placement.row_offset != box.r0 || vote.placement.col_offset != box.c0)
        return "place not confirmed";
    if (!aim_holds(grid, box.r0, box.c0, aim_field, index_, options_.vote, options_.aim))
        return "place does not hold at the aim";
    return nullptr;
}

bool Detector::place_aim(const GreyView& im, const Eigen::Matrix3d& field_to_image, const Eigen::Vector2d& aim,
                         Detection& out) const {
    const Eigen::Matrix3d i2f = field_to_image.inverse();
    const auto seed = apply_homography(i2f, aim);
    if (!seed) return false;
    out.image_to_field = i2f / i2f(2, 2);
    out.aim_field = *seed;
    if (options_.aim_refit_modules <= 0) return true;
    const auto fits_well = [&](const AimRefit& r) {
        return r.edges_fitted >= options_.aim_refit_min_share * r.edges_found;
    };
    auto refit = refit_at_aim(im, field_to_image, *seed, aim, out);
    if (!refit || !fits_well(*refit)) {
        const Eigen::Vector2d shift =
            centring_shift(im, index_.field(), brightness_, field_to_image, *seed, options_.centring);
        Eigen::Matrix3d centred = Eigen::Matrix3d::Identity();
        centred.topRightCorner<2, 1>() = shift;
        // Where neither start fits well the first refit stands: two refits
        // that fit alike can end a quarter module apart on a faint or
        // demodulated field, and which one fits a single edge more is then
        // down to rounding (the page's WebAssembly and the native build
        // parted there).
        const auto again = refit_at_aim(im, field_to_image * centred, *seed - shift, aim, out);
        if (again && fits_well(*again) && (!refit || again->edges_fitted > refit->edges_fitted)) refit = again;
    }
    if (refit) out.aim_field = refit->aim_field;
    return true;
}

std::optional<Detector::AimRefit> Detector::refit_at_aim(const GreyView& im, const Eigen::Matrix3d& field_to_image,
                                                         const Eigen::Vector2d& from, const Eigen::Vector2d& aim,
                                                         Detection& out) const {
    RefineOptions around = options_.refine;
    around.max_radius_modules = options_.aim_refit_modules;
    const Refinement r =
        refine_homography(im, index_.field(), edges_, field_to_image, from, around, out.pixels_visited);
    if (!r.refined) return std::nullopt;
    const auto refitted = apply_homography(r.field_to_image.inverse(), aim);
    // The refit searches edges within 0.4 module of the start's prediction;
    // farther off, it took hold of something else.
    if (!refitted || (*refitted - from).norm() > 0.4) return std::nullopt;
    return AimRefit{*refitted, r.edges_fitted, r.edges_found_last};
}

Eigen::Matrix3d image_to_field_through_aim(const Detection& d) {
    const auto at_aim = apply_homography(d.image_to_field, d.aim_image);
    if (!at_aim) return d.image_to_field;
    Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
    shift.topRightCorner<2, 1>() = d.aim_field - *at_aim;
    Eigen::Matrix3d h = shift * d.image_to_field;
    return h / h(2, 2);
}

Detection Detector::follow(const GreyView& im, const Eigen::Vector2d& aim,
                           const Eigen::Matrix3d& predicted_image_to_field) const {
    Detection out;
    out.aim_image = aim;
    const auto start = StageClock::now();
    auto t = start;
    auto finish = [&](const char* failure) {
        out.failure = failure ? failure : "";
        out.times.total_ms = std::chrono::duration<double, std::milli>(StageClock::now() - start).count();
        return out;
    };
    if (auto problem = describe_invalid(im); !problem.empty()) return finish("invalid image");
    const Field& f = index_.field();
    const Eigen::Matrix3d predicted_f2i = predicted_image_to_field.inverse();
    auto seed = apply_homography(predicted_image_to_field, aim);
    if (!seed || !predicted_f2i.allFinite()) return finish("prediction unusable");
    // The refit and the check below read most of the frame's cache lines,
    // out of order: fetched in order first, they cost less.
    bring_into_cache(im);
    const Refinement r = refine_homography(im, f, edges_, predicted_f2i, *seed, options_.refine, out.pixels_visited);
    out.times.refine_ms = ms_since(t);
    if (!r.refined) return finish("too few module edges near the prediction");

    if (const char* refused = confirm_place(im, r.field_to_image, aim, out)) return finish(refused);
    if (!place_aim(im, r.field_to_image, aim, out)) return finish("aim point at infinity");
    out.edges_fitted = r.edges_fitted;
    out.from_prior = true;
    out.found = true;
    return finish(nullptr);
}

}  // namespace umf
