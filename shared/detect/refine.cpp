#include "shared/detect/refine.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

namespace umf {

namespace {

struct FoundEdge {
    Point2 at;
    Point2 across;  // the image direction it was searched along (unit)
    double gradient;
};

// The vertex of the parabola through a peak of g and its neighbours, as an
// offset from the peak's sample in [-0.5, 0.5].
double vertex_offset(double g_before, double g_peak, double g_after) {
    const double denom = g_before - 2 * g_peak + g_after;
    return denom < 0 ? std::clamp(0.5 * (g_before - g_after) / denom, -0.5, 0.5) : 0.0;
}

// An edge found between samples more than a pixel apart, placed again from
// samples a pixel apart within a sample's reach of `near`.
std::optional<FoundEdge> peak_a_pixel_apart(const GreyView& im, const Point2& near, const Point2& dir,
                                            double polarity, double gradient) {
    double profile[7];
    for (int k = -3; k <= 3; ++k) {
        const Point2 q = near + k * dir;
        profile[k + 3] = bilinear(im, q.x(), q.y());
        if (!std::isfinite(profile[k + 3])) return std::nullopt;
    }
    double g[5];  // at -2 .. 2 pixels
    for (int k = 0; k < 5; ++k) g[k] = polarity * (profile[k + 2] - profile[k]) / 2;
    int peak = 2;
    if (g[1] > g[peak]) peak = 1;
    if (g[3] > g[peak]) peak = 3;
    return FoundEdge{near + (peak - 2 + vertex_offset(g[peak - 1], g[peak], g[peak + 1])) * dir, dir, gradient};
}

// Searches one edge; where it lies and how strong it is, or nothing.
// Peaks stronger than max_gradient belong to something else (text, a
// picture's edge) and are passed over for the strongest peak below it.
// `a_pixel_apart`: the peak placed from samples a pixel apart at the end.
std::optional<FoundEdge> find_edge(const GreyView& im, const Eigen::Matrix3d& h, const ExpectedEdge& e,
                                   const RefineOptions& o, double max_gradient, long& visited, bool a_pixel_apart) {
    auto p = apply_homography(h, e.mid);
    auto a = apply_homography(h, e.mid + 0.5 * e.across);
    auto b = apply_homography(h, e.mid - 0.5 * e.across);
    if (!p || !a || !b) return std::nullopt;
    Point2 dir = *a - *b;  // one module across, in the image
    const double module_px = dir.norm();
    if (module_px < o.min_module_px) return std::nullopt;
    dir /= module_px;
    // Wider than the profile holds (a homography gone wild): no edge of this field.
    const double half_width = std::ceil(o.search_modules * module_px);
    if (!(half_width <= 64)) return std::nullopt;
    // Samples a fixed fraction of a module apart, never closer than a
    // pixel: on large modules (1280 x 720 and up) a profile one pixel apart
    // costs twice what it does at 640 x 480 and places the edge no better
    // than the fit of eighty of them needs.
    const double step = std::max(1.0, module_px * o.sample_modules);
    // A peak is found strictly inside the profile: as far out as a pixel
    // apart, whatever the spacing.
    const int reach = std::max(2, 1 + static_cast<int>(std::ceil((half_width - 1) / step)));
    if (reach > 64) return std::nullopt;
    // The profile across the edge, and its derivative (grey levels per
    // pixel) towards the expected brighter side.
    double profile[2 * 64 + 3];
    for (int t = -reach - 1; t <= reach + 1; ++t) {
        const Point2 q = *p + (t * step) * dir;
        const double v = bilinear(im, q.x(), q.y());
        if (!std::isfinite(v)) return std::nullopt;
        profile[t + reach + 1] = v;
    }
    // Neighbouring samples a pixel apart share half their four pixels.
    visited += (2 * reach + 3) * (step < 2 ? 2 : 4);
    int best = 0;
    double best_g = 0;
    double g[2 * 64 + 1];
    const double per_px = e.polarity / (2 * step);
    for (int t = -reach; t <= reach; ++t) g[t + reach] = per_px * (profile[t + reach + 2] - profile[t + reach]);
    // The peak that is strong and near the prediction: text strokes under
    // the field make peaks of their own across the whole search range.
    const double spread = 0.25 * module_px / step;
    double best_score = 0;
    for (int t = -reach + 1; t < reach; ++t) {
        const double v = g[t + reach];
        if (v < o.min_gradient || v > max_gradient || v < g[t + reach - 1] || v < g[t + reach + 1]) continue;
        if (v <= best_score) continue;  // its score is no more than v
        const double score = v * std::exp(-0.5 * t * t / (spread * spread));
        if (score > best_score) best_score = score, best_g = v, best = t;
    }
    if (best_score <= 0) return std::nullopt;
    // Before the first fit the prediction is off by up to the search's
    // reach, and alike for neighbouring edges: a vertex between samples a
    // tenth of a module apart would be biased alike for all of them and bend
    // the fit (smeared frames at 640 x 480 lost the tracker's lock on it).
    if (a_pixel_apart && step > 1) {
        visited += 14;
        return peak_a_pixel_apart(im, *p + (best * step) * dir, dir, e.polarity, best_g);
    }
    const double offset = vertex_offset(g[best + reach - 1], g[best + reach], g[best + reach + 1]);
    return FoundEdge{*p + ((best + offset) * step) * dir, dir, best_g};
}

}  // namespace

Refinement refine_homography(const GreyView& im, const Field& f, const Eigen::Matrix3d& field_to_image,
                             const Point2& seed, const RefineOptions& o, long& visited) {
    return refine_homography(im, f, ModuleEdges(f), field_to_image, seed, o, visited);
}

Refinement refine_homography(const GreyView& im, const Field& f, const ModuleEdges& field_edges,
                             const Eigen::Matrix3d& field_to_image, const Point2& seed, const RefineOptions& o,
                             long& visited) {
    Refinement out;
    out.field_to_image = field_to_image;
    // The field's box seen in the image, from the image's corners.
    const Eigen::Matrix3d to_field = field_to_image.inverse();
    double u0 = f.width, v0 = f.height, u1 = 0, v1 = 0;
    for (const Point2& corner : {Point2(0, 0), Point2(im.width, 0), Point2(0, im.height), Point2(im.width, im.height)}) {
        const Eigen::Vector3d q = to_field * Eigen::Vector3d(corner.x(), corner.y(), 1.0);
        if (q.z() <= 0) {  // the horizon is in view: the whole field may be
            u0 = v0 = 0;
            u1 = f.width, v1 = f.height;
            break;
        }
        u0 = std::min(u0, q.x() / q.z()), u1 = std::max(u1, q.x() / q.z());
        v0 = std::min(v0, q.y() / q.z()), v1 = std::max(v1, q.y() / q.z());
    }
    const double span = std::min(std::max({u1 - u0, v1 - v0, 1.0}), std::max(1.0, o.max_radius_modules));
    Eigen::Matrix3d h = field_to_image;
    double max_gradient = std::numeric_limits<double>::infinity();
    // Rings of radius 4, 6, 9, 13... modules (ring_growth: each fit must
    // predict the next ring within the search range; after a clear fit 4,
    // 12, 36...), then once more over everything with the edges the whole
    // view predicts.
    bool last = false;
    std::vector<ExpectedEdge> edges;
    // The rounds' lists, made once: a frame runs a dozen rounds of up to
    // max_edges edges, and the tracker runs one every frame.
    std::vector<Point2> from, to, across, kf, kt, ka;
    std::vector<double> strength, sorted;
    for (auto* v : {&from, &to, &across, &kf, &kt, &ka}) v->reserve(static_cast<std::size_t>(std::max(0, o.max_edges)));
    for (auto* v : {&strength, &sorted}) v->reserve(static_cast<std::size_t>(std::max(0, o.max_edges)));
    double growth = o.ring_growth;
    for (double radius = 4;; radius = std::min(radius * growth, span)) {
        growth = o.ring_growth;
        // The edges whose midpoints lie within `radius` (modules, Chebyshev)
        // of the seed and inside the field's visible box, spread evenly when
        // there are too many.
        const int c_lo = std::max(0, static_cast<int>(std::floor(std::max(u0, seed.x() - radius))));
        const int c_hi = std::min(f.width - 1, static_cast<int>(std::ceil(std::min(u1, seed.x() + radius))));
        const int r_lo = std::max(0, static_cast<int>(std::floor(std::max(v0, seed.y() - radius))));
        const int r_hi = std::min(f.height - 1, static_cast<int>(std::ceil(std::min(v1, seed.y() + radius))));
        field_edges.spread_within(r_lo, r_hi, c_lo, c_hi, static_cast<std::size_t>(o.max_edges), edges);
        from.clear();
        across.clear();
        to.clear();
        strength.clear();
        for (const ExpectedEdge& e : edges) {
            ++out.edges_searched;
            if (auto q = find_edge(im, h, e, o, max_gradient, visited, !out.refined)) {
                from.push_back(e.mid);
                to.push_back(q->at);
                across.push_back(q->across);
                strength.push_back(q->gradient);
            }
        }
        // The field's edges are all about equally strong; text or a picture
        // edge near a predicted one is usually far stronger than a faint
        // field's, and would pull the fit towards itself.
        if (strength.size() >= 8) {
            sorted.assign(strength.begin(), strength.end());
            std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
            const double limit = o.max_strength_ratio * sorted[sorted.size() / 2];
            max_gradient = limit;  // the next rounds look past stronger peaks
            std::size_t kept = 0;
            for (std::size_t i = 0; i < from.size(); ++i)
                if (strength[i] <= limit) {
                    from[kept] = from[i];
                    across[kept] = across[i];
                    to[kept] = to[i];
                    ++kept;
                }
            from.resize(kept);
            across.resize(kept);
            to.resize(kept);
        }
        out.edges_found += static_cast<int>(from.size());
        if (static_cast<int>(from.size()) >= o.min_edges) {
            // A robust fit first (a whole stretch of edges may belong to a
            // table's rules or a picture), then least squares without the
            // edges it places too far. Once a ring has been fitted, its fit
            // predicted this ring's edges and judges them as well: the
            // robust fit is for the first ring alone (the same places and
            // aim errors on both sets, the refit a fifth cheaper).
            std::optional<Eigen::Matrix3d> fit;
            if (out.refined) {
                fit = h;
            } else {
                const auto here = apply_homography(h, seed), next = apply_homography(h, seed + Point2(1, 0));
                const double tol = here && next ? std::max(1.0, o.tolerance_modules * (*next - *here).norm()) : 1.0;
                if (auto robust = fit_homography_robust(from, to, tol, 60, 7)) fit = robust->h;
            }
            // Then least squares on the inliers, each edge a point on a
            // line: a search across an edge says where the edge is, not
            // where along it the prediction put the search.
            for (int round = 0; fit && round < 2; ++round) {
                const auto here = apply_homography(*fit, seed), next = apply_homography(*fit, seed + Point2(1, 0));
                if (!here || !next) break;
                const double tol = std::max(1.0, o.tolerance_modules * (*next - *here).norm());
                kf.clear();
                kt.clear();
                ka.clear();
                double sq = 0;
                for (std::size_t i = 0; i < from.size(); ++i) {
                    auto q = apply_homography(*fit, from[i]);
                    if (!q) continue;
                    const double off = across[i].dot(*q - to[i]);
                    if (!(std::abs(off) <= tol)) continue;
                    kf.push_back(from[i]);
                    kt.push_back(to[i]);
                    ka.push_back(across[i]);
                    sq += off * off;
                }
                if (static_cast<int>(kf.size()) < o.min_edges) break;
                out.edges_fitted = static_cast<int>(kf.size());
                out.edges_found_last = static_cast<int>(from.size());
                out.rms_px = std::sqrt(sq / kf.size());
                // A clear fit predicts far beyond its ring (tol is a fifth of a module).
                const double module_px = tol / o.tolerance_modules;
                if (round == 1 && kf.size() >= o.clear_found_share * edges.size() &&
                    out.rms_px <= o.clear_rms_modules * module_px)
                    growth = o.clear_ring_growth;
                fit = fit_homography_to_lines(kf, kt, ka, o.along_weight);
                if (fit) {
                    h = *fit;
                    out.refined = true;
                }
            }
        }
        if (last) break;
        last = radius >= span;
    }
    out.field_to_image = h;
    return out;
}

}  // namespace umf
