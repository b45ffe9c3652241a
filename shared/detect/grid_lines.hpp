// Stage 3 of detection: the grid lines of one family. Edgels of the family
// are chained scanline to scanline into line segments; each segment is fitted
// on its own, so the lines are as precise as the edgels. Where the segments
// cross a reference line they form a projective image of equally spaced
// points, t(k) = (a k + b) / (c k + 1); fitting that labels every segment
// with its line number k.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "shared/detect/edgels.hpp"
#include "shared/detect/vanishing_points.hpp"

namespace umf {

struct GridLine {
    int index = 0;             // k: consecutive grid lines have consecutive indices
    Eigen::Vector3d line;      // homogeneous image line, normal of unit length
    int support = 0;           // edgels on it
};

struct GridLineFamily {
    bool found = false;
    std::vector<GridLine> lines;            // sorted by index
    Eigen::Vector3d vanishing_point;        // refined from the fitted lines
    double spacing_px = 0;                  // between neighbouring lines near the image centre
};

struct GridLineOptions {
    double chain_tolerance_px = 2.0;  // an edgel continues a chain if it lies this close to the prediction
    int min_chain = 3;                // edgels in a chain to count as a segment
    double max_reach = 3;             // a chain is used up to this many times its length from the reference line
    double label_tolerance = 0.2;     // of the local spacing, for a segment to belong to line k
    double unsupported_line_cost = 0.5;  // a predicted line without a segment costs this much of an average one
    int min_lines = 3;
    int ransac_iterations = 200;
    int max_hypotheses = 3;           // distinct labellings returned, best first
    std::uint64_t seed = 1;
};

// `family` is one family from find_vanishing_points; `across` is the other
// family's vanishing point, which gives the direction along which this
// family's lines follow one another.
GridLineFamily find_grid_lines(const std::vector<Edgel>& edgels, const LineFamily& family,
                               const Eigen::Vector3d& across, int width, int height, int scan_step,
                               const GridLineOptions& options = {});

// The labellings of one family's grid lines, best first, each made when it
// is first asked for. The first is the candidates' most periodic comb
// (grid_line_comb.hpp) when there is one; the others come from triples of
// neighbouring lines (a RANSAC that costs several times the rest of this
// stage), and a frame whose first labellings read as the field needs none
// of them. Over text a document's own lines, parallel to the field's, may
// win the labelling; the detector tries each until the window vote accepts
// one. Holds a reference to `edgels`.
class GridLineLabellings {
public:
    GridLineLabellings(const std::vector<Edgel>& edgels, const LineFamily& family, const Eigen::Vector3d& across,
                       int width, int height, int scan_step, const GridLineOptions& options = {});
    ~GridLineLabellings();
    GridLineLabellings(GridLineLabellings&&) noexcept;
    GridLineLabellings& operator=(GridLineLabellings&&) = delete;

    // The best labelling alone; null when there is none. Valid while this lives.
    const GridLineFamily* first();
    // Up to options.max_hypotheses distinct labellings, the first first.
    const std::vector<GridLineFamily>& all();

private:
    struct State;
    std::unique_ptr<State> state_;
};

// GridLineLabellings(...).all().
std::vector<GridLineFamily> find_grid_line_hypotheses(const std::vector<Edgel>& edgels, const LineFamily& family,
                                                      const Eigen::Vector3d& across, int width, int height,
                                                      int scan_step, const GridLineOptions& options = {});

}  // namespace umf
