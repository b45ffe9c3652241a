#include "shared/detect/placement_vote.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace umf {

void GridPlacement::field_module(int i, int j, int& row, int& col) const {
    switch (quarter_turns & 3) {
        case 0: row = i, col = j; break;
        case 1: row = -j, col = i; break;
        case 2: row = -i, col = -j; break;
        default: row = j, col = -i; break;
    }
    row += row_offset;
    col += col_offset;
}

void GridPlacement::field_point(double x, double y, double& u, double& v) const {
    // The cell-index map above, extended to the cell's corners: a turned cell's
    // far edge becomes its near one, hence the "+ 1 -" terms.
    switch (quarter_turns & 3) {
        case 0: u = x, v = y; break;
        case 1: u = y, v = 1 - x; break;
        case 2: u = 1 - x, v = 1 - y; break;
        default: u = 1 - y, v = x; break;
    }
    u += col_offset;
    v += row_offset;
}

namespace {

// A placement as one sortable number; offsets are far inside +-2^20.
std::uint64_t pack(const GridPlacement& p) {
    return (static_cast<std::uint64_t>(p.quarter_turns & 3) << 42) |
           (static_cast<std::uint64_t>(p.row_offset + (1 << 20)) << 21) |
           static_cast<std::uint64_t>(p.col_offset + (1 << 20));
}

GridPlacement unpack(std::uint64_t k) {
    return {static_cast<int>(k >> 42), static_cast<int>((k >> 21) & 0x1fffff) - (1 << 20),
            static_cast<int>(k & 0x1fffff) - (1 << 20)};
}

// The placement under which the grid window at (i0, j0) is the field window m.
GridPlacement placement_of(const WindowMatch& m, int n, int i0, int j0) {
    switch (m.quarter_turns) {
        case 0: return {0, m.row - i0, m.col - j0};
        case 1: return {1, m.row + n - 1 + j0, m.col - i0};
        case 2: return {2, m.row + n - 1 + i0, m.col + n - 1 + j0};
        default: return {3, m.row - j0, m.col + n - 1 + i0};
    }
}

struct Agreement {
    long compared = 0;
    long matched = 0;
};

// The agreement of every placement within `radius` rows and columns of
// `predicted` (radius 0: its own), in the order dr, then dc, from -radius:
// one pass over the grid, as a shift of the placement only shifts the field
// module each grid module is compared with. The view may reach past the
// field's edge: modules off the field are not compared.
std::vector<Agreement> agreements_near(const ModuleGrid& g, const Field& f, const GridPlacement& predicted, int radius) {
    const int side = 2 * radius + 1;
    std::vector<Agreement> out(static_cast<std::size_t>(side) * side);
    auto inside = [&](int r, int c) { return r >= 0 && c >= 0 && r < f.height && c < f.width; };
    auto sign = [](int d) { return (d > 0) - (d < 0); };
    for (int i = 0; i < g.rows; ++i)
        for (int j = 0; j < g.cols; ++j) {
            int r, c;
            predicted.field_module(i, j, r, c);
            if (f.key == WindowKey::modules) {
                const int v = g.at(i, j);
                if (v == ModuleGrid::kUnknown) continue;
                for (int dr = -radius; dr <= radius; ++dr) {
                    if (r + dr < 0 || r + dr >= f.height) continue;
                    Agreement* a = &out[static_cast<std::size_t>(dr + radius) * side];
                    for (int dc = -radius; dc <= radius; ++dc) {
                        if (c + dc < 0 || c + dc >= f.width) continue;
                        ++a[dc + radius].compared;
                        a[dc + radius].matched += v == f.at(r + dr, c + dc);
                    }
                }
                continue;
            }
            for (int e = 0; e < 2; ++e) {
                const int i2 = i + e, j2 = j + 1 - e;
                const std::int8_t s = e == 0 ? g.right_of(i, j) : g.below(i, j);
                if (i2 >= g.rows || j2 >= g.cols || s == ModuleGrid::kUnknown) continue;
                int r2, c2;
                predicted.field_module(i2, j2, r2, c2);
                for (int dr = -radius; dr <= radius; ++dr)
                    for (int dc = -radius; dc <= radius; ++dc) {
                        if (!inside(r + dr, c + dc) || !inside(r2 + dr, c2 + dc)) continue;
                        Agreement& a = out[static_cast<std::size_t>(dr + radius) * side + dc + radius];
                        ++a.compared;
                        a.matched += s == sign(f.at(r2 + dr, c2 + dc) - f.at(r + dr, c + dc));
                    }
            }
        }
    return out;
}

// Calls agree(i, j) for every complete window of a module-keyed grid whose
// modules all read as the field's under p, row by row: the windows that
// vote for p, since the field's windows are unique, turned too (without
// looking each one up).
template <typename Agree>
void matching_windows(const ModuleGrid& g, const Field& f, const GridPlacement& p, int n, Agree agree) {
    // Per column, the matching modules that end at the current row; per
    // row, the columns in a row whose runs are n long.
    std::vector<int> run(static_cast<std::size_t>(g.cols), 0);
    for (int i = 0; i < g.rows; ++i) {
        int columns = 0;
        for (int j = 0; j < g.cols; ++j) {
            int r, c;
            p.field_module(i, j, r, c);
            const std::int8_t v = g.at(i, j);
            const bool match = v != ModuleGrid::kUnknown && r >= 0 && c >= 0 && r < f.height && c < f.width &&
                               v == f.at(r, c);
            int& k = run[static_cast<std::size_t>(j)];
            k = match ? k + 1 : 0;
            columns = k >= n ? columns + 1 : 0;
            if (columns >= n) agree(i - n + 1, j - n + 1);
        }
    }
}

// Calls known(i, j, placement) for every complete window of the grid that is
// a window of the field, with the placement it implies; counts the windows
// read and known into `out`.
template <typename Known>
void read_windows(const ModuleGrid& grid, const WindowIndex& index, VoteResult& out, Known known) {
    const int n = index.codec().window();
    for (int i = 0; i + n <= grid.rows; ++i)
        for (int j = 0; j + n <= grid.cols; ++j) {
            auto code = observed_code(grid, index.codec(), i, j);
            if (!code) continue;
            ++out.windows_read;
            auto match = index.find(*code);
            if (!match) continue;
            ++out.windows_known;
            known(i, j, placement_of(*match, n, i, j));
        }
}

// Bits by which the read grid favours placement p over chance, before the
// cost of choosing p among `hypotheses`.
double evidence_bits(const Agreement& a, const Field& f, const VoteOptions& options) {
    const double chance = f.key == WindowKey::modules ? 1.0 / f.colors : 1.0 / 3.0;
    const double eps = options.misread_rate;
    const double per_match = std::log2((1 - eps) / chance), per_miss = std::log2(eps / (1 - chance));
    return a.matched * per_match + (a.compared - a.matched) * per_miss;
}

}  // namespace

VoteResult vote_placement(const ModuleGrid& grid, const WindowIndex& index, const VoteOptions& options) {
    VoteResult out;
    const int n = index.codec().window();
    std::vector<std::uint64_t> ballots;
    std::vector<std::pair<int, int>> where;  // window corner of each ballot, before sorting
    const std::size_t windows = static_cast<std::size_t>(std::max(0, grid.rows - n + 1)) * std::max(0, grid.cols - n + 1);
    ballots.reserve(windows);
    where.reserve(windows);
    read_windows(grid, index, out, [&](int i, int j, const GridPlacement& p) {
        ballots.push_back(pack(p));
        where.emplace_back(i, j);
    });
    const std::vector<std::uint64_t> unsorted = ballots;
    if (ballots.empty()) return out;
    std::sort(ballots.begin(), ballots.end());
    std::uint64_t best = 0;
    for (std::size_t a = 0; a < ballots.size();) {
        std::size_t b = a;
        while (b < ballots.size() && ballots[b] == ballots[a]) ++b;
        const int count = static_cast<int>(b - a);
        if (count > out.votes) {
            out.runner_up = out.votes;
            out.votes = count;
            best = ballots[a];
        } else if (count > out.runner_up) {
            out.runner_up = count;
        }
        a = b;
    }
    out.placement = unpack(best);
    for (std::size_t k = 0; k < unsorted.size(); ++k)
        if (unsorted[k] == best) {
            out.centre_x += where[k].second + n / 2.0;
            out.centre_y += where[k].first + n / 2.0;
        }
    out.centre_x /= out.votes;
    out.centre_y /= out.votes;
    const Field& f = index.field();
    const Agreement a = agreements_near(grid, f, out.placement, 0).front();
    out.agreement = a.compared ? static_cast<double>(a.matched) / a.compared : 0.0;
    // Log-likelihood ratio of "this placement" against "chance", less the
    // bits needed to single out one of the placements.
    out.evidence_bits = evidence_bits(a, f, options) - std::log2(4.0 * static_cast<double>(f.window_count()));
    out.found = out.votes >= options.min_votes && out.votes > 2 * out.runner_up &&
                out.agreement >= options.min_agreement && out.evidence_bits >= options.min_evidence_bits;
    return out;
}

VoteResult vote_near(const ModuleGrid& grid, const WindowIndex& index, const GridPlacement& predicted, int radius,
                     const VoteOptions& options) {
    VoteResult out;
    const Field& f = index.field();
    const int side = 2 * radius + 1;
    const double choice_bits = std::log2(static_cast<double>(side) * side);
    double best_bits = -1e300, second_bits = -1e300;
    Agreement best_agreement;
    const std::vector<Agreement> near = agreements_near(grid, f, predicted, radius);
    for (int dr = -radius; dr <= radius; ++dr)
        for (int dc = -radius; dc <= radius; ++dc) {
            const GridPlacement p{predicted.quarter_turns, predicted.row_offset + dr, predicted.col_offset + dc};
            const Agreement& a = near[static_cast<std::size_t>(dr + radius) * side + dc + radius];
            const double bits = evidence_bits(a, f, options);
            if (bits > best_bits) {
                second_bits = best_bits;
                best_bits = bits;
                best_agreement = a;
                out.placement = p;
            } else if (bits > second_bits) {
                second_bits = bits;
            }
        }
    out.agreement = best_agreement.compared ? static_cast<double>(best_agreement.matched) / best_agreement.compared : 0.0;
    out.evidence_bits = best_bits - choice_bits;
    out.margin_bits = best_bits - second_bits;
    // Complete windows that agree: the same count the global vote reports.
    const int n = index.codec().window();
    auto vote = [&](int i, int j) {
        ++out.votes;
        out.centre_x += j + n / 2.0;
        out.centre_y += i + n / 2.0;
    };
    if (f.key == WindowKey::modules) {
        matching_windows(grid, f, out.placement, n, vote);
    } else {
        read_windows(grid, index, out, [&](int i, int j, const GridPlacement& q) {
            if (pack(q) == pack(out.placement)) vote(i, j);
        });
    }
    if (out.votes > 0) {
        out.centre_x /= out.votes;
        out.centre_y /= out.votes;
    } else {
        out.centre_x = grid.cols / 2.0;
        out.centre_y = grid.rows / 2.0;
    }
    out.found = out.agreement >= options.min_agreement && out.evidence_bits >= options.min_evidence_bits &&
                out.margin_bits >= options.min_evidence_bits;
    return out;
}

}  // namespace umf
