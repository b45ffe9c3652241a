#include "shared/detect/homography.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

using namespace umf;

namespace {

Eigen::Matrix3d some_perspective() {
    Eigen::Matrix3d h;
    h << 0.9, -0.3, 120, 0.25, 1.1, 40, 0.0004, -0.0007, 1;
    return h;
}

std::vector<Point2> grid_points(int n, double spacing) {
    std::vector<Point2> pts;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) pts.emplace_back(j * spacing, i * spacing);
    return pts;
}

// The images of `from` under `truth`, but for the points `wrong` picks:
// those go anywhere in a 400 x 400 square.
template <typename Wrong>
std::vector<Point2> with_wrong_matches(const std::vector<Point2>& from, const Eigen::Matrix3d& truth, unsigned seed,
                                       Wrong wrong) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> anywhere(0, 400);
    std::vector<Point2> to;
    for (std::size_t i = 0; i < from.size(); ++i) {
        if (wrong(i))
            to.emplace_back(anywhere(rng), anywhere(rng));
        else
            to.push_back(*apply_homography(truth, from[i]));
    }
    return to;
}

TEST(Homography, RecoversAnExactMapping) {
    const Eigen::Matrix3d truth = some_perspective();
    auto from = grid_points(5, 37.0);
    std::vector<Point2> to;
    for (const auto& p : from) to.push_back(*apply_homography(truth, p));
    auto h = fit_homography(from, to);
    ASSERT_TRUE(h);
    EXPECT_LT((*h - truth).norm(), 1e-6 * truth.norm());
    // Four points are enough.
    std::vector<Point2> f4{from[0], from[4], from[20], from[24]}, t4{to[0], to[4], to[20], to[24]};
    auto h4 = fit_homography(f4, t4);
    ASSERT_TRUE(h4);
    EXPECT_LT((*apply_homography(*h4, from[12]) - to[12]).norm(), 1e-6);
}

TEST(Homography, DerivativeIsHowThePointMovesThere) {
    const Eigen::Matrix3d h = some_perspective();
    const Point2 at(300, 200);
    const auto d = homography_derivative(h, at);
    ASSERT_TRUE(d.has_value());
    constexpr double kStep = 1e-4;
    for (int j = 0; j < 2; ++j) {
        const Point2 along = at + kStep * Point2::Unit(j);
        const Eigen::Vector2d numeric = (*apply_homography(h, along) - *apply_homography(h, at)) / kStep;
        EXPECT_LT((d->col(j) - numeric).norm(), 1e-4 * numeric.norm()) << "column " << j;
    }
    // A point on the horizon goes to infinity.
    Eigen::Matrix3d flat = Eigen::Matrix3d::Identity();
    flat(2, 0) = -1;
    EXPECT_FALSE(homography_derivative(flat, Point2(1, 5)).has_value());
}

TEST(Homography, RefusesTooFewOrDegeneratePoints) {
    std::vector<Point2> three{{0, 0}, {1, 0}, {0, 1}};
    EXPECT_FALSE(fit_homography(three, three));
    std::vector<Point2> line{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}};
    EXPECT_FALSE(fit_homography(line, line));
    std::vector<Point2> same(6, Point2(2, 3));
    EXPECT_FALSE(fit_homography(same, same));
    std::vector<Point2> four{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    EXPECT_FALSE(fit_homography(four, three));  // sizes differ
}

TEST(Homography, AveragesNoise) {
    const Eigen::Matrix3d truth = some_perspective();
    auto from = grid_points(10, 20.0);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.3);
    std::vector<Point2> to;
    for (const auto& p : from) to.push_back(*apply_homography(truth, p) + Point2(noise(rng), noise(rng)));
    auto h = fit_homography(from, to);
    ASSERT_TRUE(h);
    Point2 centre(90, 90);
    EXPECT_LT((*apply_homography(*h, centre) - *apply_homography(truth, centre)).norm(), 0.2);
}

TEST(Homography, RobustFitIgnoresWrongMatches) {
    const Eigen::Matrix3d truth = some_perspective();
    auto from = grid_points(8, 25.0);
    // A third of the matches are wrong.
    const std::vector<Point2> to = with_wrong_matches(from, truth, 5, [](std::size_t i) { return i % 3 == 1; });
    const int wrong = static_cast<int>((from.size() + 1) / 3);
    EXPECT_FALSE(fit_homography(from, to) &&
                 (*apply_homography(*fit_homography(from, to), from[0]) - to[0]).norm() < 0.5);
    auto r = fit_homography_robust(from, to, 1.0);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->inliers, static_cast<int>(from.size()) - wrong);
    for (std::size_t i = 0; i < from.size(); ++i) EXPECT_EQ(r->inlier[i], i % 3 != 1) << i;
    EXPECT_LT((*apply_homography(r->h, Point2(77, 99)) - *apply_homography(truth, Point2(77, 99))).norm(), 1e-6);
    // Deterministic for a seed.
    auto again = fit_homography_robust(from, to, 1.0);
    EXPECT_EQ(again->h, r->h);
}

TEST(Homography, RobustFitOfFourPointsIsExactAndRefusesThreeOnALine) {
    const Eigen::Matrix3d truth = some_perspective();
    const std::vector<Point2> from{{0, 0}, {300, 10}, {20, 250}, {280, 270}};
    const auto none = [](std::size_t) { return false; };
    const std::vector<Point2> to = with_wrong_matches(from, truth, 1, none);
    auto r = fit_homography_robust(from, to, 0.5);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->inliers, 4);
    EXPECT_LT((*apply_homography(r->h, Point2(150, 140)) - *apply_homography(truth, Point2(150, 140))).norm(), 1e-6);
    // The fourth point on the line through the first and second: no sample
    // pins a homography down.
    std::vector<Point2> on_line = from;
    on_line[3] = Point2(600, 20);
    EXPECT_FALSE(fit_homography_robust(on_line, with_wrong_matches(on_line, truth, 1, none), 0.5));
}

TEST(Homography, RobustFitDrawsOnWhenMostMatchesAreWrong) {
    // The sampling stops once a sample of four inliers has surely come up,
    // judged by the best inlier share so far; with three in five matches
    // wrong that takes all the draws allowed.
    const Eigen::Matrix3d truth = some_perspective();
    auto from = grid_points(10, 20.0);
    const std::vector<Point2> to = with_wrong_matches(from, truth, 11, [](std::size_t i) { return i % 5 < 3; });
    const int right = static_cast<int>(from.size()) * 2 / 5;
    auto r = fit_homography_robust(from, to, 1.0, 400);
    ASSERT_TRUE(r);
    EXPECT_GE(r->inliers, right);
    EXPECT_LT((*apply_homography(r->h, Point2(90, 90)) - *apply_homography(truth, Point2(90, 90))).norm(), 1e-6);
}

// Module edges as a search finds them: each field edge's midpoint, found in
// the image somewhere along the edge's image (here: `slide` pixels from where
// the truth puts the midpoint), with the image normal it was searched along.
struct FoundEdges {
    std::vector<Point2> from, to, normal;
};

FoundEdges edges_found(const Eigen::Matrix3d& truth, int n, double slide) {
    FoundEdges e;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            for (const Point2& across : {Point2(1, 0), Point2(0, 1)}) {
                const Point2 mid = Point2(c, r) * 10.0 + 5.0 * (Point2(1, 1) - across);
                const Point2 a = *apply_homography(truth, mid - 0.5 * across);
                const Point2 b = *apply_homography(truth, mid + 0.5 * across);
                const Point2 normal = (b - a).normalized();
                const Point2 along(-normal.y(), normal.x());
                e.from.push_back(mid);
                e.to.push_back(*apply_homography(truth, mid) + slide * along);
                e.normal.push_back(normal);
            }
    return e;
}

TEST(Homography, LineFitTakesEachEdgeWhereverAlongItItWasFound) {
    const Eigen::Matrix3d truth = some_perspective();
    const FoundEdges exact = edges_found(truth, 6, 0.0);
    auto h = fit_homography_to_lines(exact.from, exact.to, exact.normal);
    ASSERT_TRUE(h);
    EXPECT_LT((*h - truth).norm(), 1e-6 * truth.norm());
    // Found a pixel and a half along their edges: the lines are the same, and
    // so is the fit; a fit to the points is pulled off.
    const FoundEdges slid = edges_found(truth, 6, 1.5);
    h = fit_homography_to_lines(slid.from, slid.to, slid.normal);
    ASSERT_TRUE(h);
    const Point2 centre(30, 30);
    EXPECT_LT((*apply_homography(*h, centre) - *apply_homography(truth, centre)).norm(), 1e-6);
    auto by_points = fit_homography(slid.from, slid.to);
    ASSERT_TRUE(by_points);
    EXPECT_GT((*apply_homography(*by_points, centre) - *apply_homography(truth, centre)).norm(), 0.1);
}

TEST(Homography, LineFitRefusesTooFewOrParallelLines) {
    const Eigen::Matrix3d truth = some_perspective();
    const FoundEdges e = edges_found(truth, 6, 0.0);
    const std::vector<Point2> f7(e.from.begin(), e.from.begin() + 7), t7(e.to.begin(), e.to.begin() + 7),
        n7(e.normal.begin(), e.normal.begin() + 7);
    EXPECT_FALSE(fit_homography_to_lines(f7, t7, n7));
    // Only the edges across u: nothing says where anything is along them.
    FoundEdges one_way;
    for (std::size_t i = 0; i < e.from.size(); i += 2) {
        one_way.from.push_back(e.from[i]);
        one_way.to.push_back(e.to[i]);
        one_way.normal.push_back(e.normal[i]);
    }
    EXPECT_FALSE(fit_homography_to_lines(one_way.from, one_way.to, one_way.normal));
    EXPECT_FALSE(fit_homography_to_lines(e.from, e.to, f7));  // sizes differ
}

// A weak pull along each line: where the lines run one way it alone says
// where things are along them; where they cross, a point found off along
// its edge moves the fit by a fraction of what a fit to the points would.
TEST(Homography, LineFitWithAWeakPullAlongEachEdge) {
    const Eigen::Matrix3d truth = some_perspective();
    const FoundEdges e = edges_found(truth, 6, 0.0);
    FoundEdges one_way;
    for (std::size_t i = 0; i < e.from.size(); i += 2) {
        one_way.from.push_back(e.from[i]);
        one_way.to.push_back(e.to[i]);
        one_way.normal.push_back(e.normal[i]);
    }
    auto h = fit_homography_to_lines(one_way.from, one_way.to, one_way.normal, 0.1);
    ASSERT_TRUE(h);
    EXPECT_LT((*h - truth).norm(), 1e-6 * truth.norm());

    const Point2 centre(30, 30);
    const FoundEdges slid = edges_found(truth, 6, 1.5);
    auto by_points = fit_homography(slid.from, slid.to);
    h = fit_homography_to_lines(slid.from, slid.to, slid.normal, 0.1);
    ASSERT_TRUE(h && by_points);
    const double off = (*apply_homography(*h, centre) - *apply_homography(truth, centre)).norm();
    const double off_by_points = (*apply_homography(*by_points, centre) - *apply_homography(truth, centre)).norm();
    EXPECT_GT(off, 0);
    EXPECT_LT(off, 0.05 * off_by_points);
}

}  // namespace

TEST(Homography, ShapeDistanceIgnoresAShiftAndMeasuresAScale) {
    Eigen::Matrix3d a;
    a << 0.05, 0.01, 3, -0.01, 0.05, 7, 1e-5, 2e-5, 1;
    Eigen::Matrix3d shifted = a;
    shifted.row(0) += 2.5 * a.row(2);  // the same map, 2.5 units along x
    const Point2 at(320, 240);
    EXPECT_NEAR(shape_distance(a, shifted, at, 64), 0, 1e-9);
    Eigen::Matrix3d scaled = a;
    scaled.topRows<2>() *= 1.1;  // ten percent larger, about the origin of its units
    const double d = shape_distance(a, scaled, at, 64);
    // The ring's farthest point is some 4.5 units from `at` under a.
    EXPECT_GT(d, 0.3);
    EXPECT_LT(d, 0.6);
    EXPECT_LT(shape_distance(a, scaled, at, 8), d / 4);
    Eigen::Matrix3d vanishing = a;
    vanishing.row(2) << -1.0 / 256, 0, 1;  // the line x = 256, through the ring, sent to infinity
    EXPECT_TRUE(std::isinf(shape_distance(a, vanishing, at, 64)));
}
