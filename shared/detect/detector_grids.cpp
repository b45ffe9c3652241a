// From a scan's edgels to the grids read (steps 2 to 4 of the detector's
// pipeline): the vanishing points, each family's labellings of grid lines,
// the grid homography from their crossings, and the pairs of labellings
// tried in order, in two passes (the first pass's likeliest few of every
// search, the second the rest). Where the scans come from is in
// detector_search.cpp, what a grid becomes in detector.cpp.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/stage_time.hpp"

namespace umf {

namespace {

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

const char* Detector::search(const GreyView& im, const Eigen::Vector2d& aim, const DetectionPrior* prior,
                             const VanishingOptions& vanishing, const EdgelScan& scan, Pass& pass,
                             Detection& out) const {
    // The second pass goes over the searches the first one left pairs in,
    // with the labellings the first one found.
    const std::size_t this_search = pass.search++;
    std::vector<GridLineFamily> hypotheses[2];
    std::optional<GridLineLabellings> labellings[2];
    if (pass.first()) {
        pass.left.emplace_back();
        if (const char* failure = find_labellings(im, vanishing, scan, out, labellings)) return failure;
    } else {
        if (this_search >= pass.left.size() || pass.left[this_search].family[0].empty()) return "no grid homography";
        for (int f = 0; f < 2; ++f) hypotheses[f] = std::move(pass.left[this_search].family[f]);
    }

    // Steps 4 to 8 for each pair of labellings, the likeliest first, until
    // the window vote accepts one. The first pair comes from each family's
    // first labelling alone; the others are made only when it fails.
    const char* failure = "no grid homography";
    auto try_pair = [&](const GridLineFamily& rows_family, const GridLineFamily& cols_family) {
        auto t = StageClock::now();
        Eigen::Matrix3d g2i;
        int rows = 0, cols = 0;
        const bool fitted = grid_homography(rows_family, cols_family, im, g2i, rows, cols);
        out.times.grid_ms += ms_since(t);
        if (fitted) failure = read_grid(im, aim, prior, g2i, rows, cols, out);
        return fitted && (!failure || failure == kAimAtInfinity);
    };
    if (pass.first()) {
        if (try_pair(*labellings[0]->first(), *labellings[1]->first())) return failure;
        auto t = StageClock::now();
        for (int f = 0; f < 2; ++f) hypotheses[f] = labellings[f]->all();
        for (int f = 0; f < 2; ++f) add_halved_labellings(hypotheses[f], hypotheses[1 - f].front().spacing_px);
        out.times.grid_ms += ms_since(t);
    }
    const int n0 = static_cast<int>(hypotheses[0].size()), n1 = static_cast<int>(hypotheses[1].size());
    int ordinal = 0;
    for (int sum = 0; sum <= n0 + n1 - 2; ++sum)
        for (int h0 = std::max(0, sum - n1 + 1); h0 <= std::min(sum, n0 - 1); ++h0, ++ordinal) {
            if (ordinal < pass.first_pair || (pass.first() && ordinal == 0)) continue;
            if (ordinal >= pass.end_pair) {
                if (pass.first() && pass.plan.second_pass)
                    for (int f = 0; f < 2; ++f) pass.left[this_search].family[f] = std::move(hypotheses[f]);
                return failure;
            }
            if (try_pair(hypotheses[0][h0], hypotheses[1][sum - h0])) return failure;
        }
    return failure;
}

const char* Detector::find_labellings(const GreyView& im, const VanishingOptions& vanishing, const EdgelScan& scan,
                                      Detection& out, std::optional<GridLineLabellings> (&labellings)[2]) const {
    auto t = StageClock::now();
    // Step 2. The two vanishing points.
    const VanishingPoints vp = find_vanishing_points(scan.edgels, im.width, im.height, vanishing, scan.noise_sigma);
    out.times.vanishing_ms += ms_since(t);
    if (!vp.found) return "no grid directions";

    // Step 3. Grid lines of both families: each family's best labelling.
    for (int f = 0; f < 2; ++f) {
        labellings[f].emplace(scan.edgels, vp.family[f], vp.family[1 - f].vanishing_point, im.width, im.height,
                              scan.step, options_.grid);
        if (!labellings[f]->first()) {
            out.times.grid_ms += ms_since(t);
            return "no grid lines";
        }
    }
    out.times.grid_ms += ms_since(t);
    return nullptr;
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
