#include "detect/detector.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "detect/aim_check.hpp"
#include "detect/field_edgels.hpp"
#include "detect/homography.hpp"

namespace umf {

namespace {

using Clock = std::chrono::steady_clock;

// Grey levels of pixel noise above which scanlines are read three pixels wide
// when a first search failed (a phone's camera in dim light).
constexpr double kNoisyImage = 3.0;

// The one failure that ends a search at once: a place was accepted, but the
// aim maps to infinity under it.
constexpr const char* kAimAtInfinity = "aim point at infinity";

double ms_since(Clock::time_point& t) {
    const auto now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - t).count();
    t = now;
    return ms;
}

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

// Small modules: a family's lines labelled at half the module (text lines
// or a blurred module's two flanks between the true ones) spaces them half
// as far as the other family's. Modules are square and the view at most
// moderately foreshortened, so such a labelling also stands for the two
// that keep every other line: the even labels, and the odd ones.
void add_halved_labellings(std::vector<GridLineFamily>& family, double other_spacing) {
    const std::size_t n = family.size();
    for (std::size_t h = 0; h < n; ++h) {
        if (!(family[h].spacing_px > 0) || family[h].spacing_px > 0.7 * other_spacing) continue;
        for (int parity = 0; parity < 2; ++parity) {
            GridLineFamily halved = family[h];
            halved.lines.clear();
            for (const GridLine& line : family[h].lines)
                if (((line.index % 2) + 2) % 2 == parity) {
                    halved.lines.push_back(line);
                    halved.lines.back().index = (line.index - parity) / 2;
                }
            if (halved.lines.size() < 3) continue;
            // Indices from 0, as every labelling's are.
            const int first = halved.lines.front().index;
            for (GridLine& line : halved.lines) line.index -= first;
            halved.spacing_px *= 2;
            family.push_back(std::move(halved));
        }
    }
}

}  // namespace

Detector::Detector(const Field& field, DetectorOptions options) : index_(field), options_(std::move(options)) {}

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

Detection Detector::detect(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior) const {
    Detection out;
    out.aim_image = aim;
    const auto start = Clock::now();
    if (auto problem = describe_invalid(im); !problem.empty()) {
        out.failure = "invalid image: " + problem;
        return out;
    }
    Pass pass;
    pass.end_pair = options_.first_pass_pairs > 0 ? options_.first_pass_pairs : std::numeric_limits<int>::max();
    const char* failure = search_sizes(im, aim, prior, pass, out);
    const bool left = std::any_of(pass.left.begin(), pass.left.end(),
                                  [](const Pass::Labellings& l) { return !l.family[0].empty(); });
    if (failure && failure != kAimAtInfinity && left) {
        pass.first_pair = pass.end_pair;
        pass.end_pair = std::numeric_limits<int>::max();
        pass.first = false;
        pass.search = 0;
        const char* again = search_sizes(im, aim, prior, pass, out);
        if (!again || again == kAimAtInfinity) failure = again;
    }
    out.failure = failure ? failure : "";
    out.times.total_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    return out;
}

const char* Detector::search_sizes(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                   Pass& pass, Detection& out) const {
    const char* failure = search_smaller(im, aim, prior, pass, out);
    if (!failure) return nullptr;
    if (pass.first && options_.lattice_enabled && !search_lattice(im, aim, prior, out)) return nullptr;
    const int max_side = options_.double_size_max_side;
    if (max_side > 0 && std::max(im.width, im.height) <= max_side) {
        // The part around the aim, at double size: as many pixels as the frame.
        const double part = std::clamp(options_.double_size_part, 0.1, 1.0);
        const int w = std::max(8, static_cast<int>(std::lround(im.width * part)));
        const int h = std::max(8, static_cast<int>(std::lround(im.height * part)));
        if (w <= im.width && h <= im.height) {
            const int x0 = std::clamp(static_cast<int>(std::lround(aim.x() - w / 2.0)), 0, im.width - w);
            const int y0 = std::clamp(static_cast<int>(std::lround(aim.y() - h / 2.0)), 0, im.height - h);
            const GreyView around{im.row(y0) + x0, w, h, im.stride};
            if (!search_resized(around, 2, Eigen::Vector2d(x0, y0), aim, prior, pass, out)) return nullptr;
        }
    }
    return failure;
}

const char* Detector::search_lattice(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                     Detection& out) const {
    auto t = Clock::now();
    const std::vector<Lattice> lattices = find_lattices(im, aim, options_.lattice);
    out.times.grid_ms += ms_since(t);
    out.pixels_visited += static_cast<long>(options_.lattice.patch_px) * options_.lattice.patch_px;
    const char* failure = "no lattice";
    for (const Lattice& l : lattices) {
        failure = read_grid(im, aim, prior, l.grid_to_image, l.rows, l.cols, out);
        if (!failure) out.from_lattice = true;
        if (!failure || failure == kAimAtInfinity) return failure;
    }
    return failure;
}

const char* Detector::search_smaller(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                     Pass& pass, Detection& out) const {
    const char* failure = search_scans(im, aim, prior, options_.vanishing, pass, out);
    const int min_side = options_.half_size_min_side;
    if (!failure || min_side <= 0 || std::min(im.width, im.height) / 2 < min_side) return failure;
    return search_resized(im, 0.5, Eigen::Vector2d::Zero(), aim, prior, pass, out) ? failure : nullptr;
}

const char* Detector::search_resized(const GreyView& part, double scale, const Eigen::Vector2d& origin,
                                     const Eigen::Vector2d& aim, const DetectionPrior* prior, Pass& pass,
                                     Detection& out) const {
    auto t = Clock::now();
    std::vector<std::uint8_t> pixels;
    const GreyView resized = scale < 1 ? half_size(part, pixels) : double_size(part, pixels);
    out.times.edgels_ms += ms_since(t);
    out.pixels_visited += static_cast<long>(part.width) * part.height;
    Eigen::Matrix3d to_resized;
    to_resized << scale, 0, -scale * origin.x(), 0, scale, -scale * origin.y(), 0, 0, 1;
    DetectionPrior resized_prior;
    if (prior) resized_prior = {prior->image_to_field * to_resized.inverse(), prior->radius_modules};
    const DetectionPrior* p = prior ? &resized_prior : nullptr;
    const Eigen::Vector2d resized_aim = scale * (aim - origin);
    // The places checked at the other sizes count against the ones checked
    // here (confirm_place's extra bits), as for any other candidate. Half
    // size goes on to smaller sizes; double size is the last try.
    const char* failure = nullptr;
    if (scale < 1) {
        failure = search_smaller(resized, resized_aim, p, pass, out);
    } else {
        VanishingOptions wider = options_.vanishing;
        wider.max_inlier_deg = options_.double_size_max_inlier_deg;
        failure = search_scans(resized, resized_aim, p, wider, pass, out);
    }
    if (failure) return failure;
    out.image_to_field = out.image_to_field * to_resized;
    out.aim_image = aim;
    out.size_scale *= scale;
    return nullptr;
}

const char* Detector::search_scans(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                   const VanishingOptions& vanishing, Pass& pass, Detection& out) const {
    // Step 1. Edgels on sparse scanlines; when nothing is found on them,
    // again on the scanlines half way between (small modules need closer
    // scanlines for their grid lines to chain), keeping what was read, down
    // to scanlines 4 pixels apart.
    auto t = Clock::now();
    EdgelOptions edgel_options = options_.edgels;
    EdgelScan scan = find_edgels(im, edgel_options);
    out.pixels_visited += scan.pixels_visited;
    out.times.edgels_ms += ms_since(t);
    const char* failure = search_all_then_field_like(im, aim, prior, vanishing, scan, pass, out);
    if (failure && options_.rescan && scan.noise_sigma >= kNoisyImage && edgel_options.across < 3) {
        // A noisy image (low light): a faint field's edges drown in the
        // scanlines' noise; three pixels across each line hold them, and a
        // lower bar lets the weaker ones through (the chains and the window
        // vote keep the peaks the noise makes out of the grid).
        edgel_options.across = 3;
        edgel_options.noise_deviations = options_.noisy_edge_deviations;
        t = Clock::now();
        scan = find_edgels(im, edgel_options);
        out.pixels_visited += scan.pixels_visited;
        out.times.edgels_ms += ms_since(t);
        failure = search_all_then_field_like(im, aim, prior, vanishing, scan, pass, out);
    }
    int offset = edgel_options.offset >= 0 ? edgel_options.offset : scan.step / 2;  // of the scanlines so far
    while (failure && options_.rescan && scan.step >= 8) {
        EdgelOptions between = edgel_options;
        between.step = scan.step;
        between.offset = (offset + scan.step / 2) % scan.step;
        offset = std::min(offset, between.offset);
        t = Clock::now();
        const EdgelScan more = find_edgels(im, between);
        scan.edgels.insert(scan.edgels.end(), more.edgels.begin(), more.edgels.end());
        scan.step /= 2;
        out.pixels_visited += more.pixels_visited;
        out.times.edgels_ms += ms_since(t);
        failure = search_all_then_field_like(im, aim, prior, vanishing, scan, pass, out);
    }
    return failure;
}

const char* Detector::search_all_then_field_like(const GreyView& im, const Eigen::Vector2d& aim,
                                                 const DetectionPrior* prior, const VanishingOptions& vanishing,
                                                 const EdgelScan& scan, Pass& pass, Detection& out) const {
    const char* failure = search(im, aim, prior, vanishing, scan, pass, out);
    if (!failure) return nullptr;
    // A faint field under strong content: its own edges alone (field_edgels.hpp),
    // when that leaves out enough of the others to matter; then the edges
    // less those of thin lines (a spreadsheet's rules).
    auto t = Clock::now();
    EdgelScan field_like = scan;
    field_like.edgels = edgels_stepping_by(scan.edgels, commonest_edge_step(scan.edgels));
    out.times.edgels_ms += ms_since(t);
    auto worth_a_search = [&](const EdgelScan& fewer) {
        return fewer.edgels.size() >= 40 && fewer.edgels.size() <= scan.edgels.size() * 17 / 20;
    };
    if (worth_a_search(field_like) && !search(im, aim, prior, vanishing, field_like, pass, out)) return nullptr;
    if (options_.thin_line_px <= 0) return failure;
    t = Clock::now();
    EdgelScan off_lines = scan;
    off_lines.edgels = edgels_off_thin_lines(scan.edgels, options_.thin_line_px);
    out.times.edgels_ms += ms_since(t);
    if (worth_a_search(off_lines) && !search(im, aim, prior, vanishing, off_lines, pass, out)) return nullptr;
    return failure;
}

const char* Detector::search(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                             const VanishingOptions& vanishing, const EdgelScan& scan, Pass& pass,
                             Detection& out) const {
    // The second pass goes over the searches the first one left pairs in,
    // with the labellings the first one found.
    const std::size_t this_search = pass.search++;
    std::vector<GridLineFamily> hypotheses[2];
    if (pass.first) {
        pass.left.emplace_back();
        if (const char* failure = find_labellings(im, vanishing, scan, out, hypotheses)) return failure;
    } else {
        if (this_search >= pass.left.size() || pass.left[this_search].family[0].empty()) return "no grid homography";
        for (int f = 0; f < 2; ++f) hypotheses[f] = std::move(pass.left[this_search].family[f]);
    }
    auto t = Clock::now();

    // Steps 4 to 8 for each pair of labellings, the likeliest first, until
    // the window vote accepts one.
    const char* failure = "no grid homography";
    const int n0 = static_cast<int>(hypotheses[0].size()), n1 = static_cast<int>(hypotheses[1].size());
    int ordinal = 0;
    for (int sum = 0; sum <= n0 + n1 - 2; ++sum)
        for (int h0 = std::max(0, sum - n1 + 1); h0 <= std::min(sum, n0 - 1); ++h0, ++ordinal) {
            if (ordinal < pass.first_pair) continue;
            if (ordinal >= pass.end_pair) {
                if (pass.first)
                    for (int f = 0; f < 2; ++f) pass.left[this_search].family[f] = std::move(hypotheses[f]);
                return failure;
            }
            t = Clock::now();
            Eigen::Matrix3d g2i;
            int rows = 0, cols = 0;
            const bool fitted = grid_homography(hypotheses[0][h0], hypotheses[1][sum - h0], im, g2i, rows, cols);
            out.times.grid_ms += ms_since(t);
            if (!fitted) continue;
            failure = read_grid(im, aim, prior, g2i, rows, cols, out);
            if (!failure || failure == kAimAtInfinity) return failure;
        }
    return failure;
}

const char* Detector::find_labellings(const GreyView& im, const VanishingOptions& vanishing, const EdgelScan& scan,
                                      Detection& out, std::vector<GridLineFamily> (&hypotheses)[2]) const {
    auto t = Clock::now();
    // Step 2. The two vanishing points.
    const VanishingPoints vp = find_vanishing_points(scan.edgels, im.width, im.height, vanishing, scan.noise_sigma);
    out.times.vanishing_ms += ms_since(t);
    if (!vp.found) return "no grid directions";

    // Step 3. Grid lines of both families: a few labellings of each, best first.
    for (int f = 0; f < 2; ++f) {
        hypotheses[f] = find_grid_line_hypotheses(scan.edgels, vp.family[f], vp.family[1 - f].vanishing_point,
                                                  im.width, im.height, scan.step, options_.grid);
        if (hypotheses[f].empty()) {
            out.times.grid_ms += ms_since(t);
            return "no grid lines";
        }
    }
    for (int f = 0; f < 2; ++f) add_halved_labellings(hypotheses[f], hypotheses[1 - f].front().spacing_px);
    out.times.grid_ms += ms_since(t);
    return nullptr;
}

const char* Detector::read_grid(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                                const Eigen::Matrix3d& g2i, int rows, int cols, Detection& out) const {
    // Step 5. Module values or edge signs.
    auto t = Clock::now();
    ++out.grids_read;
    const Field& f = index_.field();
    const ModuleGrid grid = classify_modules(im, g2i, rows, cols, f.colors, f.key == WindowKey::edges,
                                             options_.classify, out.pixels_visited);
    out.times.classify_ms += ms_since(t);

    // Step 6. Window lookup and the placement vote: near the predicted place
    // first, when there is a prior; the whole field's vote when that finds
    // nothing or its place is refused.
    t = Clock::now();
    VoteResult near;
    if (prior) {
        if (auto predicted = predict_placement(prior->image_to_field, g2i, rows, cols))
            near = vote_near(grid, index_, *predicted, prior->radius_modules, options_.vote);
    }
    out.times.vote_ms += ms_since(t);
    Eigen::Matrix3d field_to_image;
    int edges_fitted = 0;
    const char* refused = near.found ? place_from_vote(im, aim, g2i, near, out, field_to_image, edges_fitted) : nullptr;
    const bool near_prior = near.found && !refused;
    t = Clock::now();
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
        if (weak || (near.found && near.placement == vote.placement)) return refused ? refused : "no agreeing windows";
        refused = place_from_vote(im, aim, g2i, vote, out, field_to_image, edges_fitted);
        t = Clock::now();
    }
    if (refused) return refused;
    out.edges_fitted = edges_fitted;
    const bool placed = place_aim(im, field_to_image, aim, out);
    out.times.refine_ms += ms_since(t);
    if (!placed) return kAimAtInfinity;
    out.from_prior = near_prior;
    out.found = true;
    return nullptr;
}

const char* Detector::place_from_vote(const GreyView& im, const Eigen::Vector2d& aim, const Eigen::Matrix3d& g2i,
                                      const VoteResult& vote, Detection& out, Eigen::Matrix3d& field_to_image,
                                      int& edges_fitted) const {
    auto t = Clock::now();
    const Eigen::Matrix3d voted_f2i = g2i * placement_matrix(vote.placement).inverse();
    field_to_image = voted_f2i;
    edges_fitted = 0;
    // Step 7. Module edges around the voting windows, then outwards.
    if (options_.refine_enabled) {
        double su, sv;
        vote.placement.field_point(vote.centre_x, vote.centre_y, su, sv);
        const Refinement r =
            refine_homography(im, index_.field(), field_to_image, Point2(su, sv), options_.refine, out.pixels_visited);
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

bool Detector::grid_homography(const GridLineFamily& rows_family, const GridLineFamily& cols_family,
                               const GreyView& im, Eigen::Matrix3d& g2i, int& rows, int& cols) const {
    // Step 4. The grid homography from the crossings of the lines. Family 1
    // lines are x = const, family 0 lines y = const, unless that mirrors the
    // image: the field is never seen from behind.
    std::vector<Point2> grid_pts, image_pts;
    for (const auto& a : rows_family.lines)
        for (const auto& b : cols_family.lines) {
            const Eigen::Vector3d p = a.line.cross(b.line);
            if (std::abs(p.z()) < 1e-12) continue;
            const Point2 q(p.x() / p.z(), p.y() / p.z());
            if (q.x() < 0 || q.y() < 0 || q.x() > im.width || q.y() > im.height) continue;
            grid_pts.emplace_back(b.index, a.index);
            image_pts.push_back(q);
        }
    auto fit = fit_homography_robust(grid_pts, image_pts, options_.corner_tolerance_px, 100, 1);
    if (!fit || fit->inliers < 8) return false;
    g2i = fit->h;
    rows = rows_family.lines.back().index;
    cols = cols_family.lines.back().index;
    const Point2 c(cols / 2.0, rows / 2.0);
    auto p0 = apply_homography(g2i, c), px = apply_homography(g2i, c + Point2(1, 0)),
         py = apply_homography(g2i, c + Point2(0, 1));
    if (!p0 || !px || !py) return false;
    const Point2 ex = *px - *p0, ey = *py - *p0;
    if (ex.x() * ey.y() - ex.y() * ey.x() < 0) {
        Eigen::Matrix3d swap;
        swap << 0, 1, 0, 1, 0, 0, 0, 0, 1;
        g2i = g2i * swap;
        std::swap(rows, cols);
    }
    return true;
}

}  // namespace umf

namespace umf {

const char* Detector::confirm_place(const GreyView& im, const Eigen::Matrix3d& field_to_image, const Eigen::Vector2d& aim,
                                    Detection& out, double extra_bits) const {
    // The modules of the field's visible box, read under the homography: the
    // grid is the field itself, so the expected placement is a plain offset,
    // and it must beat its neighbours one module away.
    auto t = Clock::now();
    const Field& f = index_.field();
    const Eigen::Matrix3d i2f = field_to_image.inverse();
    double u0 = f.width, v0 = f.height, u1 = 0, v1 = 0;
    const double front = (i2f * Eigen::Vector3d(aim.x(), aim.y(), 1.0)).z();  // sign of points on the screen
    for (const Point2& corner : {Point2(0, 0), Point2(im.width, 0), Point2(0, im.height), Point2(im.width, im.height)}) {
        auto q = apply_homography(i2f, corner);
        if (!q || (i2f * Eigen::Vector3d(corner.x(), corner.y(), 1.0)).z() * front <= 0) {
            u0 = v0 = 0, u1 = f.width, v1 = f.height;
            break;
        }
        u0 = std::min(u0, q->x()), u1 = std::max(u1, q->x());
        v0 = std::min(v0, q->y()), v1 = std::max(v1, q->y());
    }
    const int c0 = std::max(0, static_cast<int>(std::floor(u0))), r0 = std::max(0, static_cast<int>(std::floor(v0)));
    const int c1 = std::min(f.width, static_cast<int>(std::ceil(u1))), r1 = std::min(f.height, static_cast<int>(std::ceil(v1)));
    if (c1 - c0 < 2 || r1 - r0 < 2) return "place not confirmed";
    Eigen::Matrix3d shift;
    shift << 1, 0, c0, 0, 1, r0, 0, 0, 1;
    const ModuleGrid grid = classify_modules(im, field_to_image * shift, r1 - r0, c1 - c0, f.colors,
                                             f.key == WindowKey::edges, options_.classify, out.pixels_visited);
    out.times.classify_ms += ms_since(t);
    VoteOptions vote_options = options_.vote;
    vote_options.min_evidence_bits += extra_bits;
    VoteResult vote = vote_near(grid, index_, GridPlacement{0, r0, c0}, 1, vote_options);
    out.times.vote_ms += ms_since(t);
    out.windows = vote.votes;
    out.confidence = vote.agreement;
    if (!vote.found || vote.placement.row_offset != r0 || vote.placement.col_offset != c0)
        return "place not confirmed";
    const Eigen::Vector3d a = i2f * Eigen::Vector3d(aim.x(), aim.y(), 1.0);
    if (!aim_holds(grid, r0, c0, a.hnormalized(), index_, options_.vote, options_.aim))
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
    RefineOptions around = options_.refine;
    around.max_radius_modules = options_.aim_refit_modules;
    const Refinement r = refine_homography(im, index_.field(), field_to_image, *seed, around, out.pixels_visited);
    if (!r.refined) return true;
    const auto refitted = apply_homography(r.field_to_image.inverse(), aim);
    // The refit searches edges within 0.4 module of the whole view's
    // prediction; farther off, it took hold of something else.
    if (!refitted || (*refitted - *seed).norm() > 0.4) return true;
    out.aim_field = *refitted;
    return true;
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
    const auto start = Clock::now();
    auto t = start;
    auto finish = [&](const char* failure) {
        out.failure = failure ? failure : "";
        out.times.total_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        return out;
    };
    if (auto problem = describe_invalid(im); !problem.empty()) return finish("invalid image");
    const Field& f = index_.field();
    const Eigen::Matrix3d predicted_f2i = predicted_image_to_field.inverse();
    auto seed = apply_homography(predicted_image_to_field, aim);
    if (!seed || !predicted_f2i.allFinite()) return finish("prediction unusable");
    const Refinement r = refine_homography(im, f, predicted_f2i, *seed, options_.refine, out.pixels_visited);
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
