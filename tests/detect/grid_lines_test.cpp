#include "shared/detect/grid_lines.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using Case = test::PhotoCase;

// Blank screens: over text the document's own lines, parallel to the field's,
// can win the first labelling; the detector's tests cover busy screens, where
// the window vote chooses among the labellings.
class GridLinesOnPhotos : public ::testing::TestWithParam<Case> {};

TEST_P(GridLinesOnPhotos, LieOnTheFieldsModuleBoundariesInOrder) {
    const Case c = GetParam();
    Field f = test::shipped_field("b4-64x36.json");
    test::Photo photo = test::photograph_field(f, c.opacity, c.pitch, c.yaw, c.roll, c.distance, c.screen);
    GreyView view = photo.view();
    auto scan = find_edgels(view);
    auto vp = find_vanishing_points(scan.edgels, view.width, view.height);
    ASSERT_TRUE(vp.found);
    for (int fam = 0; fam < 2; ++fam) {
        auto lines = find_grid_lines(scan.edgels, vp.family[fam], vp.family[1 - fam].vanishing_point, view.width,
                                     view.height, scan.step);
        ASSERT_TRUE(lines.found) << c.name << " family " << fam;
        EXPECT_GE(lines.lines.size(), 6u) << c.name;
        int checked = 0, good = 0;
        std::vector<std::pair<int, long>> index_value;  // line index, field line number
        for (const auto& gl : lines.lines) {
            // Two points on the line near the image centre, in field coordinates.
            const Eigen::Vector2d n = gl.line.head<2>(), d(-n.y(), n.x());
            const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
            const Eigen::Vector2d p0 = centre - (n.dot(centre) + gl.line.z()) * n;
            if ((p0 - centre).norm() > 200) continue;
            cv::Point2d a = sim::image_to_field(photo.shot, photo.placement, {p0.x() - 30 * d.x(), p0.y() - 30 * d.y()});
            cv::Point2d b = sim::image_to_field(photo.shot, photo.placement, {p0.x() + 30 * d.x(), p0.y() + 30 * d.y()});
            const bool const_u = std::abs(a.x - b.x) < std::abs(a.y - b.y);
            const double va = const_u ? a.x : a.y, vb = const_u ? b.x : b.y;
            ++checked;
            const long integer = std::lround((va + vb) / 2);
            if (std::abs(va - integer) < 0.1 && std::abs(vb - integer) < 0.1) ++good;
            index_value.emplace_back(gl.index, integer);
        }
        EXPECT_GE(checked, 4) << c.name;
        EXPECT_EQ(good, checked) << c.name << " family " << fam;
        // Consecutive indices are neighbouring field lines.
        bool consistent = true;
        for (std::size_t i = 1; i < index_value.size(); ++i) {
            const long dv = index_value[i].second - index_value[0].second;
            const int dk = index_value[i].first - index_value[0].first;
            consistent &= std::abs(dv) == std::abs(dk);
        }
        EXPECT_TRUE(consistent) << c.name << " family " << fam;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Poses, GridLinesOnPhotos,
    ::testing::Values(Case{"straight", sim::ScreenKind::blank, 0.5, 0, 0, 0, 300},
                      Case{"rolled", sim::ScreenKind::blank, 0.5, 0, 0, 33, 300},
                      Case{"tilted", sim::ScreenKind::blank, 0.5, 40, -25, 20, 250}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

// The first labelling is made without the triples and is the first of all
// of them; over a document the others are there for the detector to try.
TEST(GridLineLabellings, TheFirstIsMadeAloneAndLeadsAllOfThem) {
    Field f = test::shipped_field("b4-64x36.json");
    test::Photo photo = test::photograph_field(f, 0.3, 10, -15, 5, 300, sim::ScreenKind::document);
    GreyView view = photo.view();
    auto scan = find_edgels(view);
    auto vp = find_vanishing_points(scan.edgels, view.width, view.height);
    ASSERT_TRUE(vp.found);
    for (int fam = 0; fam < 2; ++fam) {
        GridLineLabellings labellings(scan.edgels, vp.family[fam], vp.family[1 - fam].vanishing_point, view.width,
                                      view.height, scan.step);
        const GridLineFamily* first_made = labellings.first();
        ASSERT_NE(first_made, nullptr) << "family " << fam;
        const GridLineFamily first = *first_made;
        const std::vector<GridLineFamily>& all = labellings.all();
        ASSERT_GE(all.size(), 2u) << "family " << fam;
        ASSERT_EQ(all.front().lines.size(), first.lines.size());
        for (std::size_t k = 0; k < first.lines.size(); ++k) {
            EXPECT_EQ(all.front().lines[k].index, first.lines[k].index);
            EXPECT_TRUE(all.front().lines[k].line.isApprox(first.lines[k].line));
        }
        // The same labellings a second time, from the same edgels.
        EXPECT_EQ(find_grid_line_hypotheses(scan.edgels, vp.family[fam], vp.family[1 - fam].vanishing_point,
                                            view.width, view.height, scan.step)
                      .size(),
                  all.size());
    }
}

}  // namespace
