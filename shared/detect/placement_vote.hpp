// Where a grid read from the image lies in the field: every readable window
// is looked up and votes for one placement (turn and offset); a clear winner
// that agrees with what was read is the answer, anything else is "not found".
// A wrong place is worse than none, so the thresholds lean to caution.
#pragma once

#include "shared/detect/module_grid.hpp"
#include "shared/detect/window_index.hpp"

namespace umf {

// Grid cell (i, j) shows field module (row, col) = turn(i, j) + (row_offset, col_offset),
// where turn is (i, j), (-j, i), (-i, -j) or (j, -i) for quarter_turns 0..3.
struct GridPlacement {
    int quarter_turns = 0;
    int row_offset = 0;
    int col_offset = 0;

    void field_module(int i, int j, int& row, int& col) const;
    // A continuous grid point (x along columns, y along rows, cell (i, j)
    // covering x in [j, j+1], y in [i, i+1]) in field coordinates (u, v).
    void field_point(double x, double y, double& u, double& v) const;

    bool operator==(const GridPlacement&) const = default;
};

struct VoteOptions {
    int min_votes = 2;            // windows that must agree
    double min_agreement = 0.75;  // of the read modules (or edges) the winner must explain
    // The winner must be this many bits more likely than chance, counting
    // every read module (edge) it explains or contradicts against the number
    // of placements there are to choose from: 20 bits is one false placement
    // in a million random grids. With few modules in view the evidence is not
    // there, however well the windows agree.
    double min_evidence_bits = 20;
    double misread_rate = 0.05;  // the classifier's assumed error rate per module or edge
};

struct VoteResult {
    bool found = false;
    GridPlacement placement;
    int votes = 0;          // windows that voted for the winner
    int runner_up = 0;      // votes of the best other placement
    // vote_placement: windows fully read from the grid, and of those the
    // ones found in the field (vote_near only counts those that agree).
    int windows_read = 0;
    int windows_known = 0;
    double agreement = 0;   // fraction of read modules or edges that match the field at the winner
    double evidence_bits = 0;
    double margin_bits = 0;  // vote_near: the winner's evidence over the runner-up's
    // Grid point (x along columns, y along rows) at the mean centre of the
    // windows that voted for the winner: where the grid is surely right.
    double centre_x = 0, centre_y = 0;
};

VoteResult vote_placement(const ModuleGrid& grid, const WindowIndex& index, const VoteOptions& options = {});

// The placement of a grid whose place is roughly known (from the previous
// video frame): every placement with the predicted turn and an offset within
// `radius` of the predicted one is scored on all modules read, not only on
// complete windows, and the best wins when its evidence against these few
// hypotheses reaches the threshold and beats the runner-up's by as much
// again. `votes` counts the complete windows that agree with the winner.
VoteResult vote_near(const ModuleGrid& grid, const WindowIndex& index, const GridPlacement& predicted, int radius,
                     const VoteOptions& options = {});

}  // namespace umf
