#include "shared/detect/grid_lines.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <span>

#include "shared/detect/grid_line_comb.hpp"

namespace umf {

namespace {

struct Chain {
    std::vector<int> members;  // edgel indices, one per scanline
    Eigen::Vector3d line;      // total-least-squares fit, unit normal
    double t = 0;              // where it crosses the reference line
};

// Total least squares: the line through the centroid along the principal axis.
Eigen::Vector3d fit_line(const std::vector<Edgel>& edgels, const std::vector<int>& members) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int i : members) mean += Eigen::Vector2d(edgels[i].x, edgels[i].y);
    mean /= static_cast<double>(members.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (int i : members) {
        const Eigen::Vector2d d = Eigen::Vector2d(edgels[i].x, edgels[i].y) - mean;
        cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    const Eigen::Vector2d normal = eig.eigenvectors().col(0);
    return {normal.x(), normal.y(), -normal.dot(mean)};
}

// Where a line crosses the reference line c + t u; NaN when it runs along it.
double crossing(const Eigen::Vector3d& l, const Eigen::Vector2d& c, const Eigen::Vector2d& u) {
    const double along = l.head<2>().dot(u);
    if (std::abs(along) < 1e-6) return std::numeric_limits<double>::quiet_NaN();
    return -(l.head<2>().dot(c) + l.z()) / along;
}

// t(k) = (a k + b) / (c k + 1), fitted to labelled crossings in the linear
// form a k + b - c k t = t.
bool fit_projective_1d(std::span<const std::pair<int, double>> kt, std::span<const double> w, double& a, double& b,
                       double& c) {
    if (kt.size() < 3) return false;
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Vector3d atb = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < kt.size(); ++i) {
        const double k = kt[i].first, t = kt[i].second;
        const Eigen::Vector3d row(k, 1.0, -k * t);
        ata += w[i] * row * row.transpose();
        atb += w[i] * row * t;
    }
    Eigen::Vector3d x = ata.ldlt().solve(atb);
    if (!x.allFinite()) return false;
    a = x(0);
    b = x(1);
    c = x(2);
    return true;
}

// Step 3: one line per label, fitted to all its edgels. The vanishing point
// is refined where the well-supported lines meet; a line with few edgels is
// better placed by the model: through that point and its predicted crossing t(k).
template <typename Chains, typename Candidates>
GridLineFamily build_family(const std::vector<Edgel>& edgels, const Chains& chains, const Candidates& cand,
                            const std::vector<std::pair<int, int>>& labels, double ba, double bb, double bc,
                            const Eigen::Vector3d& vp, const Eigen::Vector2d& centre, const Eigen::Vector2d& u,
                            int min_lines) {
    GridLineFamily out;
    constexpr int kWellSupported = 6;
    std::map<int, std::vector<int>> members_of;
    for (auto [i, k] : labels)
        for (int ch : cand[i].chains)
            members_of[k].insert(members_of[k].end(), chains[ch].members.begin(), chains[ch].members.end());
    if (members_of.empty()) return out;
    const int k_min = members_of.begin()->first;
    Eigen::Matrix3d mm = Eigen::Matrix3d::Zero();
    int strong = 0;
    for (auto& [k, members] : members_of) {
        GridLine gl;
        gl.index = k - k_min;
        gl.line = fit_line(edgels, members);
        gl.support = static_cast<int>(members.size());
        if (gl.support >= kWellSupported) {
            mm += gl.support * gl.line * gl.line.transpose();
            ++strong;
        }
        out.lines.push_back(gl);
    }
    if (static_cast<int>(out.lines.size()) < min_lines) return out;
    if (strong >= 2) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(mm);
        out.vanishing_point = eig.eigenvectors().col(0).normalized();
    } else {
        out.vanishing_point = vp;
    }
    for (auto& gl : out.lines) {
        if (gl.support >= kWellSupported) continue;
        const int k = gl.index + k_min;
        const double t = (ba * k + bb) / (bc * k + 1);
        const Eigen::Vector2d p = centre + t * u;
        Eigen::Vector3d l = Eigen::Vector3d(p.x(), p.y(), 1.0).cross(out.vanishing_point);
        const double n = l.head<2>().norm();
        if (n > 1e-12) gl.line = l / n;
    }
    const double t0 = bb, t1 = (ba + bb) / (bc + 1);
    out.spacing_px = std::abs(t1 - t0);
    out.found = true;
    return out;
}


// A family's edgels by the scanline they lie on, each kept only on the
// scanlines (rows or columns) that cross its line most steeply, sorted by
// position along the scanline; columns first, then rows, each by coordinate.
struct Scanlines {
    std::vector<std::vector<int>> lists;       // per scanline, edgel indices by position
    std::vector<Eigen::Vector2d> direction;    // per edgel index: towards the vanishing point
    int columns_from = 0, rows_from = 0;       // the first column's and first row's coordinates
    int columns = 0;                           // lists [0, columns) are columns, the rest rows

    bool on_row(std::size_t list) const { return static_cast<int>(list) >= columns; }
    // The scanline `distance` further on from `list`, of the same kind; null when it holds nothing.
    const std::vector<int>* find(std::size_t list, int distance) const {
        const int at = static_cast<int>(list) + distance;
        const bool row = on_row(list);
        if (row ? at >= static_cast<int>(lists.size()) : at >= columns) return nullptr;
        return lists[at].empty() ? nullptr : &lists[at];
    }
};

Scanlines steep_scanlines(const std::vector<Edgel>& edgels, const std::vector<int>& members, const Eigen::Vector3d& vp) {
    Scanlines out;
    out.direction.resize(edgels.size());
    int lo[2] = {std::numeric_limits<int>::max(), std::numeric_limits<int>::max()}, hi[2] = {-1, -1};
    std::vector<int> kept;
    for (int i : members) {
        const Edgel& e = edgels[i];
        const Eigen::Vector2d dir = direction_to(vp, {e.x, e.y});
        out.direction[i] = dir;
        const bool steep = std::abs(dir.y()) >= std::abs(dir.x());
        if (steep != e.on_row) continue;
        const int line = static_cast<int>(std::lround(e.on_row ? e.y : e.x));
        lo[e.on_row] = std::min(lo[e.on_row], line);
        hi[e.on_row] = std::max(hi[e.on_row], line);
        kept.push_back(i);
    }
    out.columns_from = hi[0] >= 0 ? lo[0] : 0;
    out.rows_from = hi[1] >= 0 ? lo[1] : 0;
    out.columns = hi[0] >= 0 ? hi[0] - lo[0] + 1 : 0;
    out.lists.resize(static_cast<std::size_t>(out.columns) + (hi[1] >= 0 ? hi[1] - lo[1] + 1 : 0));
    for (int i : kept) {
        const Edgel& e = edgels[i];
        const int line = static_cast<int>(std::lround(e.on_row ? e.y : e.x));
        out.lists[e.on_row ? out.columns + line - out.rows_from : line - out.columns_from].push_back(i);
    }
    for (std::size_t s = 0; s < out.lists.size(); ++s) {
        const bool row = out.on_row(s);
        std::sort(out.lists[s].begin(), out.lists[s].end(), [&edgels, row](int a, int b) {
            return row ? edgels[a].x < edgels[b].x : edgels[a].y < edgels[b].y;
        });
    }
    return out;
}

}  // namespace

// Chains of edgels, the candidate lines they make where they cross the
// reference line, and the labellings made of them so far.
struct GridLineLabellings::State {
    struct Candidate {
        double t;
        double weight;
        std::vector<int> chains;
    };
    struct Hypothesis {
        double score = 0;
        std::vector<std::pair<int, int>> labels;  // (candidate, k)
        double a = 0, b = 0, c = 0;
    };
    struct Hit {
        int k, candidate;
        double miss;
    };

    const std::vector<Edgel>& edgels;
    GridLineOptions o;
    int width, height;
    Eigen::Vector3d vp;
    Eigen::Vector2d centre, u;
    std::vector<Chain> chains;
    std::vector<Candidate> cand;
    double mean_weight = 0;
    std::vector<Hit> hits;  // reused by every call of label()
    std::optional<Hypothesis> comb;
    std::optional<GridLineFamily> comb_family;  // the comb's lines, once made (found or not)
    bool all_made = true;  // until there are candidates to label, there is nothing to make
    std::vector<GridLineFamily> all;

    State(const std::vector<Edgel>& e, const GridLineOptions& options, int w, int h)
        : edgels(e), o(options), width(w), height(h) {}

    // Labels every candidate that lies on a predicted line, at most one per
    // line (the nearest), and scores the labelling by the edgels it explains.
    double label(double a, double b, double c, std::vector<std::pair<int, int>>& labels);
    // The labelling refitted to all its candidates and its lines fitted.
    GridLineFamily finish(Hypothesis best);
    // Labellings from triples of neighbouring candidates, best first.
    std::vector<Hypothesis> triples();
};

double GridLineLabellings::State::label(double a, double b, double c, std::vector<std::pair<int, int>>& labels) {
    hits.clear();
    for (int i = 0; i < static_cast<int>(cand.size()); ++i) {
        // Invert t(k): k = (t - b) / (a - c t).
        const double t = cand[i].t, den = a - c * t;
        if (std::abs(den) < 1e-9) continue;
        const double kf = (t - b) / den;
        if (!(std::abs(kf) < 1e4)) continue;
        const int k = static_cast<int>(std::lround(kf));
        // Both ends of the step must lie on the same branch of the map.
        if ((c * k + 1) <= 0 || (c * (k + 1) + 1) <= 0) continue;
        const double tk = (a * k + b) / (c * k + 1), tk1 = (a * (k + 1) + b) / (c * (k + 1) + 1);
        const double spacing = std::abs(tk1 - tk), miss = std::abs(t - tk);
        if (!(spacing > 3.0) || miss > o.label_tolerance * spacing) continue;
        hits.push_back({k, i, miss});
    }
    // At most one candidate per line: the nearest.
    std::sort(hits.begin(), hits.end(),
              [](const Hit& x, const Hit& y) { return x.k != y.k ? x.k < y.k : x.miss < y.miss; });
    labels.clear();
    double score = 0;
    for (std::size_t h = 0; h < hits.size(); ++h) {
        if (h > 0 && hits[h].k == hits[h - 1].k) continue;
        labels.emplace_back(hits[h].candidate, hits[h].k);
        score += cand[hits[h].candidate].weight;
    }
    // A grid of half the true spacing explains every line and every stray
    // edge between them; lines it predicts but nothing supports cost it.
    // Not a whole line's worth each: over text many true lines break into
    // pieces too short to chain, and at full cost a grid of twice the
    // spacing, skipping them, would win.
    if (!labels.empty()) {
        const int span = labels.back().second - labels.front().second + 1;
        score -= o.unsupported_line_cost * mean_weight * (span - static_cast<int>(labels.size()));
    }
    return score;
}

std::vector<GridLineLabellings::State::Hypothesis> GridLineLabellings::State::triples() {
    std::mt19937_64 rng(o.seed);
    std::vector<Hypothesis> tried;
    std::vector<std::pair<int, int>> labels;
    const int m = static_cast<int>(cand.size());
    std::vector<char> drawn_before(static_cast<std::size_t>(m) * 6, 0);
    for (int it = 0; it < o.ransac_iterations; ++it) {
        // Three neighbouring candidates, taken as lines 0, 1, 2 (or 0, 1, 3
        // and 0, 2, 3 when one line between them was missed).
        const int i = static_cast<int>(rng() % std::max(1, m - 2));
        if (i + 2 >= m) break;
        static const int patterns[3][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}};
        const int* p = patterns[it % 3];
        const int j = i + 1, l = i + 2 + (it % 3 != 0 && i + 3 < m && (rng() & 1) ? 1 : 0);
        if (l >= m) continue;
        // A triple drawn before gives the same labelling again.
        char& drawn = drawn_before[(static_cast<std::size_t>(i) * 2 + (l - i - 2)) * 3 + it % 3];
        if (drawn) continue;
        drawn = 1;
        const std::pair<int, double> kt[3] = {{p[0], cand[i].t}, {p[1], cand[j].t}, {p[2], cand[l].t}};
        static constexpr double kEqual[3] = {1, 1, 1};
        double a, b, c;
        if (!fit_projective_1d(kt, kEqual, a, b, c)) continue;
        const double score = label(a, b, c, labels);
        // Its labels are made again if it is chosen (label() is a pure function of a, b, c).
        if (score > 0 && static_cast<int>(labels.size()) >= o.min_lines) tried.push_back({score, {}, a, b, c});
    }
    std::stable_sort(tried.begin(), tried.end(), [](const Hypothesis& x, const Hypothesis& y) { return x.score > y.score; });
    return tried;
}

GridLineFamily GridLineLabellings::State::finish(Hypothesis best) {
    // Refit to every labelled candidate, then label again with the refit.
    std::vector<std::pair<int, int>> labels;
    for (int round = 0; round < 2; ++round) {
        std::vector<std::pair<int, double>> kt;
        std::vector<double> w;
        for (auto [i, k] : best.labels) {
            kt.emplace_back(k, cand[i].t);
            w.push_back(cand[i].weight);
        }
        double a, b, c;
        if (!fit_projective_1d(kt, w, a, b, c)) break;
        const double score = label(a, b, c, labels);
        if (score < best.score) break;
        best = {score, labels, a, b, c};
    }
    return build_family(edgels, chains, cand, best.labels, best.a, best.b, best.c, vp, centre, u, o.min_lines);
}

GridLineLabellings::GridLineLabellings(const std::vector<Edgel>& edgels, const LineFamily& family,
                                       const Eigen::Vector3d& across, int width, int height, int scan_step,
                                       const GridLineOptions& o)
    : state_(std::make_unique<State>(edgels, o, width, height)) {
    State& st = *state_;
    if (family.edgels.size() < 3 || scan_step <= 0) return;
    const Eigen::Vector3d& vp = family.vanishing_point;
    st.vp = vp;

    // Step 1: chain edgels from scanline to scanline along the direction to
    // the vanishing point. Each edgel is chained through the scanlines that
    // cross its line most steeply.
    const Scanlines scanlines = steep_scanlines(edgels, family.edgels, vp);
    std::vector<int> next(edgels.size(), -1), has_prev(edgels.size(), 0);
    // Module edges come and go along a grid line (neighbouring modules are
    // often equal), so a chain may skip a few scanlines.
    constexpr int kMaxSkip = 4;
    for (std::size_t s = 0; s < scanlines.lists.size(); ++s) {
        const bool row = scanlines.on_row(s);
        for (const int i : scanlines.lists[s]) {
            const Edgel& e = edgels[i];
            const Eigen::Vector2d& dir = scanlines.direction[i];
            for (int skip = 1; skip <= kMaxSkip && next[i] < 0; ++skip) {
                const std::vector<int>* there = scanlines.find(s, skip * scan_step);
                if (!there) continue;
                // Move along the line to that scanline.
                const double step = row ? skip * scan_step / dir.y() : skip * scan_step / dir.x();
                const double predicted = row ? e.x + step * dir.x() : e.y + step * dir.y();
                const double reach = o.chain_tolerance_px * (1 + 0.25 * (skip - 1));
                auto position = [&](int j) -> double { return row ? edgels[j].x : edgels[j].y; };
                // The list is sorted by position: only those within reach can
                // be nearest, and the first of equals wins, as in a full pass.
                auto it = std::lower_bound(there->begin(), there->end(), predicted - reach - 1e-9,
                                           [&](int j, double p) { return position(j) <= p; });
                int best = -1;
                double best_d = reach;
                for (; it != there->end() && position(*it) < predicted + reach + 1e-9; ++it) {
                    const double d = std::abs(position(*it) - predicted);  // the test of a full pass
                    if (d < best_d && !has_prev[*it]) {
                        best_d = d;
                        best = *it;
                    }
                }
                if (best >= 0) {
                    next[i] = best;
                    has_prev[best] = 1;
                }
            }
        }
    }
    const Eigen::Vector2d centre(width / 2.0, height / 2.0);
    const Eigen::Vector2d u = direction_to(across, centre);
    st.centre = centre;
    st.u = u;
    std::vector<Chain>& chains = st.chains;
    for (const std::vector<int>& list : scanlines.lists)
        for (int i : list) {
            if (has_prev[i]) continue;
            Chain ch;
            for (int j = i; j >= 0; j = next[j]) ch.members.push_back(j);
            if (static_cast<int>(ch.members.size()) < o.min_chain) continue;
            ch.line = fit_line(edgels, ch.members);
            ch.t = crossing(ch.line, centre, u);
            if (!std::isfinite(ch.t)) continue;
            // A short chain far from the reference line crosses it where its
            // direction, fitted over a few scanlines, guesses: at small
            // module sizes a fraction of a degree there is a whole module
            // here. Such chains would only blur the labelling.
            const Edgel& first = edgels[ch.members.front()];
            const Edgel& last = edgels[ch.members.back()];
            const Eigen::Vector2d mid((first.x + last.x) / 2, (first.y + last.y) / 2);
            const double length = std::hypot(last.x - first.x, last.y - first.y);
            if ((centre + ch.t * u - mid).norm() > o.max_reach * length) continue;
            chains.push_back(std::move(ch));
        }
    if (static_cast<int>(chains.size()) < o.min_lines) return;

    // Step 2: label the chains. Chains that cross the reference line close
    // together are pieces of one line.
    std::sort(chains.begin(), chains.end(), [](const Chain& a, const Chain& b) { return a.t < b.t; });
    std::vector<State::Candidate>& cand = st.cand;
    for (int i = 0; i < static_cast<int>(chains.size()); ++i) {
        const double w = static_cast<double>(chains[i].members.size());
        if (!cand.empty() && chains[i].t - cand.back().t < 1.5) {
            auto& c = cand.back();
            c.t = (c.t * c.weight + chains[i].t * w) / (c.weight + w);
            c.weight += w;
            c.chains.push_back(i);
        } else {
            cand.push_back({chains[i].t, w, {i}});
        }
    }
    if (static_cast<int>(cand.size()) < o.min_lines) return;
    for (const auto& c : cand) st.mean_weight += c.weight;
    st.mean_weight /= static_cast<double>(cand.size());
    st.all_made = false;

    // The labelling from the spacing that makes the candidates near the
    // centre most periodic (grid_line_comb.hpp). The triples (State::triples)
    // need three clean neighbours in a row, which a document rarely leaves.
    std::vector<double> t, weight;
    for (const auto& c : cand) t.push_back(c.t), weight.push_back(c.weight);
    std::vector<std::pair<int, int>> labels;
    for (const auto& comb : periodic_labellings(t, weight, width, height)) {
        double a, b, c;
        const std::vector<double> w(comb.size(), 1.0);
        if (!fit_projective_1d(comb, w, a, b, c)) continue;
        const double score = st.label(a, b, c, labels);
        if (static_cast<int>(labels.size()) < o.min_lines) continue;
        if (!st.comb || score > st.comb->score) st.comb = State::Hypothesis{score, labels, a, b, c};
    }
}

GridLineLabellings::~GridLineLabellings() = default;
GridLineLabellings::GridLineLabellings(GridLineLabellings&&) noexcept = default;

const GridLineFamily* GridLineLabellings::first() {
    State& st = *state_;
    if (st.comb && !st.comb_family) st.comb_family = st.finish(*st.comb);
    if (st.comb_family && st.comb_family->found) return &*st.comb_family;
    const std::vector<GridLineFamily>& every = all();
    return every.empty() ? nullptr : &every.front();
}

const std::vector<GridLineFamily>& GridLineLabellings::all() {
    State& st = *state_;
    if (st.all_made) return st.all;
    st.all_made = true;
    // The comb first, then the best triples that explain other candidates:
    // over text, the document's own lines run parallel to the field's and
    // may score higher, so the caller tries each until the window vote
    // accepts one.
    std::vector<State::Hypothesis> tried = st.triples();
    if (st.comb) tried.insert(tried.begin(), *st.comb);
    std::vector<State::Hypothesis*> chosen;
    std::vector<std::vector<char>> labelled_in_chosen;  // per chosen labelling: which candidates it labels
    for (State::Hypothesis& h : tried) {
        if (static_cast<int>(chosen.size()) >= st.o.max_hypotheses) break;
        if (h.labels.empty()) st.label(h.a, h.b, h.c, h.labels);
        bool distinct = true;
        for (std::size_t c = 0; c < chosen.size(); ++c) {
            int shared = 0;
            for (auto [i, k] : h.labels) shared += labelled_in_chosen[c][i];
            distinct &= shared < 0.7 * std::min(h.labels.size(), chosen[c]->labels.size());
        }
        if (!distinct) continue;
        chosen.push_back(&h);
        labelled_in_chosen.emplace_back(st.cand.size(), 0);
        for (auto [i, k] : h.labels) labelled_in_chosen.back()[i] = 1;
    }
    for (std::size_t c = 0; c < chosen.size(); ++c) {
        const bool comb_made = c == 0 && st.comb && st.comb_family;
        GridLineFamily fam = comb_made ? *st.comb_family : st.finish(*chosen[c]);
        if (fam.found) st.all.push_back(std::move(fam));
    }
    return st.all;
}

std::vector<GridLineFamily> find_grid_line_hypotheses(const std::vector<Edgel>& edgels, const LineFamily& family,
                                                      const Eigen::Vector3d& across, int width, int height,
                                                      int scan_step, const GridLineOptions& options) {
    GridLineLabellings labellings(edgels, family, across, width, height, scan_step, options);
    return labellings.all();
}

GridLineFamily find_grid_lines(const std::vector<Edgel>& edgels, const LineFamily& family,
                               const Eigen::Vector3d& across, int width, int height, int scan_step,
                               const GridLineOptions& options) {
    auto all = find_grid_line_hypotheses(edgels, family, across, width, height, scan_step, options);
    return all.empty() ? GridLineFamily{} : std::move(all.front());
}

}  // namespace umf
