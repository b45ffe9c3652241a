// Step 7 of detection: once the place is known, the field itself says where
// every module edge must be and which side is brighter. Searching those edges
// in the image and refitting the homography to them makes the aim point as
// precise as the edges, and repairs a grid homography that was only right
// near the windows that voted: the fit starts around them and grows outwards,
// each round predicting the next ring of edges from the last fit.
#pragma once

#include <Eigen/Core>

#include "shared/detect/homography.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/module_edges.hpp"
#include "shared/field/field.hpp"

namespace umf {

struct RefineOptions {
    double search_modules = 0.4;  // how far across its predicted place an edge is looked for
    double sample_modules = 0.1;  // the profile's samples this far apart (a pixel at least)
    double min_gradient = 1.5;    // grey levels per pixel for an edge to count
    double min_module_px = 2.5;   // smaller modules are not searched
    int max_edges = 80;           // edges searched per round, spread over the region
    int min_edges = 16;           // fewer found edges leave the homography as it was
    double tolerance_modules = 0.2;  // an edge further than this from the fit is an outlier
    double max_strength_ratio = 2.5; // edges stronger than this times the median are not the field's
    double max_radius_modules = 1e9; // the rings stop at this radius (the whole view by default)
    double ring_growth = 1.5;        // each ring's radius over the last's
    // After a ring whose fit is clear (at least clear_found_share of its
    // edges fitted, their rms across the edges at most clear_rms_modules)
    // the next is clear_ring_growth times as wide: fewer rounds where the
    // vote's homography was already good (docs/BENCHMARKS.md, "wider rings
    // after a clear fit"). At 4/5 of the edges a faint field's first ring
    // over a spreadsheet's rules read as clear and the wider ring beyond
    // it put the aim half a module off (tuning set, ruled at opacity 0.08).
    double clear_ring_growth = 3;
    double clear_found_share = 0.85;
    double clear_rms_modules = 0.05;
    // Each edge is fitted as a point on its line and, this many times as
    // weakly, as the point found (fit_homography_to_lines' along_weight):
    // on the lines alone a few smeared frames at 1280 x 720 and above put
    // the aim 0.5-0.7 module off (docs/BENCHMARKS.md, "A weak pull along
    // each edge").
    double along_weight = 0.1;
};

struct Refinement {
    bool refined = false;
    Eigen::Matrix3d field_to_image = Eigen::Matrix3d::Identity();
    int edges_searched = 0;
    int edges_found = 0;
    int edges_fitted = 0;  // inliers of the last round
    int edges_found_last = 0;  // edges found in that round, inliers or not
    double rms_px = 0;     // of the inliers of the last round, across their edges
};

// `field_to_image` is the homography from the vote; `seed` the field point
// (u, v) where it is known to be right; `field_edges` the field's own.
Refinement refine_homography(const GreyView& image, const Field& field, const ModuleEdges& field_edges,
                             const Eigen::Matrix3d& field_to_image, const Point2& seed, const RefineOptions& options,
                             long& pixels_visited);
// The same, listing the field's edges first (for a single call).
Refinement refine_homography(const GreyView& image, const Field& field, const Eigen::Matrix3d& field_to_image,
                             const Point2& seed, const RefineOptions& options, long& pixels_visited);

}  // namespace umf
