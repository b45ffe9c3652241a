#include "shared/detect/homography.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace umf {

namespace {

double cube(double x) { return x * x * x; }

// Hartley's normalisation: centroid to the origin, mean distance sqrt(2), so
// the linear system is well conditioned whatever the units.
Eigen::Matrix3d normaliser(const std::vector<Point2>& pts) {
    Point2 mean = Point2::Zero();
    for (const auto& p : pts) mean += p;
    mean /= static_cast<double>(pts.size());
    double dist = 0;
    for (const auto& p : pts) dist += (p - mean).norm();
    dist /= static_cast<double>(pts.size());
    const double s = dist > 1e-12 ? std::sqrt(2.0) / dist : 1.0;
    Eigen::Matrix3d t;
    t << s, 0, -s * mean.x(), 0, s, -s * mean.y(), 0, 0, 1;
    return t;
}

using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Vector9 = Eigen::Matrix<double, 9, 1>;

// The unit vector v minimising v^T M v for the normal matrix M of a linear
// system, as a 3 x 3 matrix row by row; nothing when the system does not pin
// it down.
std::optional<Eigen::Matrix3d> smallest_eigenvector(const Matrix9& ata) {
    // Inverse iteration: that eigenvalue is next to 0 and far below the
    // others, so each step gains their ratio and three steps match a full
    // eigen-decomposition to rounding, at a fifth of its cost. The shift
    // keeps exact data solvable.
    const Eigen::LDLT<Matrix9> ldlt(ata + 1e-12 * ata.trace() * Matrix9::Identity());
    if (ldlt.info() != Eigen::Success) return std::nullopt;
    // A unique solution has one (near) zero eigenvalue; a second one means the
    // data do not pin the homography down. The pivots, largest first, of
    // the decomposition of a semi-definite matrix show it in the last two.
    Vector9 pivots = ldlt.vectorD().cwiseAbs();
    std::sort(pivots.data(), pivots.data() + 9);
    if (!(pivots(1) > 1e-9 * pivots(8))) return std::nullopt;
    Vector9 v = Vector9::Ones().normalized();
    for (int step = 0; step < 3; ++step) v = ldlt.solve(v).normalized();
    if (!v.allFinite()) return std::nullopt;
    Eigen::Matrix3d m;
    m << v(0), v(1), v(2), v(3), v(4), v(5), v(6), v(7), v(8);
    return m;
}

// A homography in its usual scale, or nothing when it is (nearly) singular.
std::optional<Eigen::Matrix3d> scaled(Eigen::Matrix3d h) {
    if (!h.allFinite() || std::abs(h.determinant()) < 1e-15 * cube(h.norm())) return std::nullopt;
    if (std::abs(h(2, 2)) > 1e-12) h /= h(2, 2);
    return h;
}

// The homography taking the projective basis (e1, e2, e3, e1 + e2 + e3) to
// four points: their columns, each scaled so the fourth is their sum.
// Nothing when three of the four are (nearly) on one line.
std::optional<Eigen::Matrix3d> from_basis(const Point2* p) {
    Eigen::Matrix3d m;
    m << p[0].x(), p[1].x(), p[2].x(), p[0].y(), p[1].y(), p[2].y(), 1, 1, 1;
    const double det = m.determinant();
    const double size = std::abs(p[1].x() - p[0].x()) + std::abs(p[1].y() - p[0].y()) + std::abs(p[2].x() - p[0].x()) +
                        std::abs(p[2].y() - p[0].y()) + std::abs(p[3].x() - p[0].x()) + std::abs(p[3].y() - p[0].y());
    // det is twice the area of p0 p1 p2; each scale below is an area over it.
    const double tiny = 1e-10 * size * size;
    if (!(std::abs(det) > tiny)) return std::nullopt;
    const Eigen::Vector3d l = m.inverse() * Eigen::Vector3d(p[3].x(), p[3].y(), 1);
    if (!(std::abs(l(0) * det) > tiny && std::abs(l(1) * det) > tiny && std::abs(l(2) * det) > tiny)) return std::nullopt;
    return m * l.asDiagonal();
}

// The homography through exactly four correspondences: the map from the
// projective basis to `to` after the inverse of the one to `from`, a few
// dozen operations against a linear solve or an eigen-decomposition for each
// of the hundreds of samples RANSAC draws. Points are centred on the first
// sample pair to keep the sums well conditioned.
std::optional<Eigen::Matrix3d> homography_from_4(const Point2* from, const Point2* to) {
    const Point2 of = from[0], ot = to[0];
    Point2 f[4], t[4];
    for (int i = 0; i < 4; ++i) {
        f[i] = from[i] - of;
        t[i] = to[i] - ot;
    }
    const auto a = from_basis(f), b = from_basis(t);
    if (!a || !b) return std::nullopt;
    Eigen::Matrix3d tf, tt;
    tf << 1, 0, -of.x(), 0, 1, -of.y(), 0, 0, 1;
    tt << 1, 0, ot.x(), 0, 1, ot.y(), 0, 0, 1;
    return scaled(tt * *b * a->inverse() * tf);
}

}  // namespace

std::optional<Point2> apply_homography(const Eigen::Matrix3d& h, const Point2& p) {
    const Eigen::Vector3d q = h * Eigen::Vector3d(p.x(), p.y(), 1.0);
    if (std::abs(q.z()) < 1e-12) return std::nullopt;
    return Point2(q.x() / q.z(), q.y() / q.z());
}

std::optional<Eigen::Matrix2d> homography_derivative(const Eigen::Matrix3d& h, const Point2& at) {
    const Eigen::Vector3d q = h * Eigen::Vector3d(at.x(), at.y(), 1.0);
    if (std::abs(q.z()) < 1e-12) return std::nullopt;
    // d(q.xy / q.z) = (H_xy - (q.xy / q.z) H_z) / q.z, column by column.
    const Eigen::Vector2d p = q.head<2>() / q.z();
    return ((h.topLeftCorner<2, 2>() - p * h.block<1, 2>(2, 0)) / q.z()).eval();
}

double shape_distance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, const Point2& at, double reach) {
    const auto pa = apply_homography(a, at), pb = apply_homography(b, at);
    if (!pa || !pb) return std::numeric_limits<double>::infinity();
    double most = 0;
    for (const double dx : {-reach, 0.0, reach})
        for (const double dy : {-reach, 0.0, reach}) {
            const Point2 q = at + Point2(dx, dy);
            const auto qa = apply_homography(a, q), qb = apply_homography(b, q);
            if (!qa || !qb) return std::numeric_limits<double>::infinity();
            most = std::max(most, ((*qa - *pa) - (*qb - *pb)).norm());
        }
    return most;
}

std::optional<Eigen::Matrix3d> fit_homography(const std::vector<Point2>& from, const std::vector<Point2>& to) {
    const std::size_t n = from.size();
    if (n < 4 || to.size() != n) return std::nullopt;
    const Eigen::Matrix3d tf = normaliser(from), tt = normaliser(to);
    // A^T A of the 2n x 9 DLT system; its eigenvector of the smallest
    // eigenvalue is the homography. A point's two rows give, in 3 x 3 blocks,
    // a a^T times [bz^2, 0, -bx bz; 0, bz^2, -by bz; -bx bz, -by bz, bx^2 + by^2]:
    // four weighted sums of a a^T hold all of it.
    Eigen::Matrix3d zz = Eigen::Matrix3d::Zero(), xz = zz, yz = zz, xy = zz;
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d a = tf * Eigen::Vector3d(from[i].x(), from[i].y(), 1.0);
        const Eigen::Vector3d b = tt * Eigen::Vector3d(to[i].x(), to[i].y(), 1.0);
        const Eigen::Matrix3d aa = a * a.transpose();
        zz += b.z() * b.z() * aa;
        xz += b.x() * b.z() * aa;
        yz += b.y() * b.z() * aa;
        xy += (b.x() * b.x() + b.y() * b.y()) * aa;
    }
    Matrix9 ata = Matrix9::Zero();
    ata.block<3, 3>(0, 0) = zz;
    ata.block<3, 3>(3, 3) = zz;
    ata.block<3, 3>(0, 6) = ata.block<3, 3>(6, 0) = -xz;
    ata.block<3, 3>(3, 6) = ata.block<3, 3>(6, 3) = -yz;
    ata.block<3, 3>(6, 6) = xy;
    const auto hn = smallest_eigenvector(ata);
    if (!hn) return std::nullopt;
    return scaled(tt.inverse() * *hn * tf);
}

std::optional<Eigen::Matrix3d> fit_homography_to_lines(const std::vector<Point2>& from, const std::vector<Point2>& to,
                                                       const std::vector<Point2>& normal, double along_weight) {
    const std::size_t n = from.size();
    if (n < 8 || to.size() != n || normal.size() != n) return std::nullopt;
    // Each row says H a lies on the line l through b across its normal:
    // l^T H a = 0, the row l (x) a. A normaliser that only scales and
    // shifts keeps a line's normal and moves its point.
    const Eigen::Matrix3d tf = normaliser(from), tt = normaliser(to);
    Matrix9 ata = Matrix9::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d a = tf * Eigen::Vector3d(from[i].x(), from[i].y(), 1.0);
        const Point2 b = (tt * Eigen::Vector3d(to[i].x(), to[i].y(), 1.0)).head<2>();
        const Eigen::Vector3d l(normal[i].x(), normal[i].y(), -normal[i].dot(b));
        const Eigen::Matrix3d aa = a * a.transpose();
        for (int r = 0; r < 3; ++r)
            for (int c = r; c < 3; ++c) ata.block<3, 3>(3 * r, 3 * c) += l(r) * l(c) * aa;
        if (along_weight > 0) {
            // The line through b along the first one: its normal is the
            // first line's direction.
            const Point2 t = along_weight * Point2(-normal[i].y(), normal[i].x());
            const Eigen::Vector3d m(t.x(), t.y(), -t.dot(b));
            for (int r = 0; r < 3; ++r)
                for (int c = r; c < 3; ++c) ata.block<3, 3>(3 * r, 3 * c) += m(r) * m(c) * aa;
        }
    }
    for (int r = 1; r < 3; ++r)
        for (int c = 0; c < r; ++c) ata.block<3, 3>(3 * r, 3 * c) = ata.block<3, 3>(3 * c, 3 * r);
    const auto hn = smallest_eigenvector(ata);
    if (!hn) return std::nullopt;
    return scaled(tt.inverse() * *hn * tf);
}

std::optional<RobustHomography> fit_homography_robust(const std::vector<Point2>& from, const std::vector<Point2>& to,
                                                      double tolerance, int iterations, std::uint64_t seed) {
    const std::size_t n = from.size();
    if (n < 4 || to.size() != n) return std::nullopt;
    std::mt19937_64 rng(seed);
    // Whether H takes from[i] within `tolerance` of to[i], without dividing:
    // |q.xy - to q.z| <= tolerance |q.z|, and q.z not (nearly) 0.
    const double tol2 = tolerance * tolerance;
    auto fits = [&](const Eigen::Matrix3d& h, std::size_t i) {
        const Eigen::Vector3d q = h * Eigen::Vector3d(from[i].x(), from[i].y(), 1.0);
        if (std::abs(q.z()) < 1e-12) return false;
        const double dx = q.x() - to[i].x() * q.z(), dy = q.y() - to[i].y() * q.z();
        return dx * dx + dy * dy <= tol2 * q.z() * q.z();
    };
    auto count_inliers = [&](const Eigen::Matrix3d& h, std::vector<bool>& mask) {
        int count = 0;
        mask.assign(n, false);
        for (std::size_t i = 0; i < n; ++i)
            if (fits(h, i)) {
                mask[i] = true;
                ++count;
            }
        return count;
    };
    // Samples are judged on an evenly spread subset of at most kJudges
    // points; only the winner is counted on all of them.
    constexpr std::size_t kJudges = 120;
    const std::size_t stride = std::max<std::size_t>(1, n / kJudges);
    // A sample's count, or any count no more than `beat` once it cannot
    // exceed it: only a better sample than the best so far changes anything.
    auto judge = [&](const Eigen::Matrix3d& h, int beat) {
        int count = 0, left = static_cast<int>((n + stride - 1) / stride);
        for (std::size_t i = 0; i < n && count + left > beat; i += stride, --left) count += fits(h, i);
        return count;
    };
    RobustHomography best;
    std::vector<bool> mask;
    std::vector<Point2> sf(4), st(4);
    int best_judged = 0;
    const int all_judges = static_cast<int>((n + stride - 1) / stride);
    constexpr double kConfidence = 0.9999;
    double needed = iterations;
    for (int it = 0; it < iterations; ++it) {
        std::size_t idx[4];
        for (int k = 0; k < 4; ++k) {
            bool fresh;
            do {
                idx[k] = static_cast<std::size_t>(rng() % n);
                fresh = true;
                for (int m = 0; m < k; ++m) fresh &= idx[m] != idx[k];
            } while (!fresh);
            sf[k] = from[idx[k]];
            st[k] = to[idx[k]];
        }
        auto h = homography_from_4(sf.data(), st.data());
        if (!h) continue;
        const int c = judge(*h, best_judged);
        if (c > best_judged) {
            best_judged = c;
            best.h = *h;
            if (c == all_judges) break;
            // Samples enough that one of them was all inliers with
            // probability kConfidence, were the best one's inliers all there
            // are; no more than `iterations` either way.
            const double all_in = std::pow(static_cast<double>(c) / all_judges, 4);
            needed = std::min<double>(iterations, std::log(1 - kConfidence) / std::log1p(-all_in));
        }
        if (it + 1 >= needed) break;
    }
    if (best_judged == 0) return std::nullopt;
    best.inliers = count_inliers(best.h, best.inlier);
    if (best.inliers < 4) return std::nullopt;
    // Refit to every inlier, then take the inliers of the refit.
    std::vector<Point2> f, t;
    f.reserve(n);
    t.reserve(n);
    for (int round = 0; round < 2; ++round) {
        f.clear();
        t.clear();
        for (std::size_t i = 0; i < n; ++i)
            if (best.inlier[i]) {
                f.push_back(from[i]);
                t.push_back(to[i]);
            }
        auto h = fit_homography(f, t);
        if (!h) break;
        const int c = count_inliers(*h, mask);
        if (c < best.inliers) break;
        best.h = *h;
        best.inliers = c;
        best.inlier = mask;
    }
    return best;
}

}  // namespace umf
