#include "detect/homography.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <random>

namespace umf {

namespace {

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

// The homography through exactly four correspondences, with h22 = 1: an
// 8 x 8 linear system, far cheaper than the eigen-decomposition of the DLT for
// the thousands of samples RANSAC draws. Points are centred on the first
// sample pair so h22 = 0 (the first point mapped to infinity) cannot occur.
std::optional<Eigen::Matrix3d> homography_from_4(const Point2* from, const Point2* to) {
    const Point2 of = from[0], ot = to[0];
    Eigen::Matrix<double, 8, 8> a;
    Eigen::Matrix<double, 8, 1> b;
    for (int i = 0; i < 4; ++i) {
        const double x = from[i].x() - of.x(), y = from[i].y() - of.y();
        const double u = to[i].x() - ot.x(), v = to[i].y() - ot.y();
        a.row(2 * i) << x, y, 1, 0, 0, 0, -u * x, -u * y;
        a.row(2 * i + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
        b(2 * i) = u;
        b(2 * i + 1) = v;
    }
    const Eigen::FullPivLU<Eigen::Matrix<double, 8, 8>> lu(a);
    if (!lu.isInvertible()) return std::nullopt;
    const Eigen::Matrix<double, 8, 1> x = lu.solve(b);
    if (!x.allFinite()) return std::nullopt;
    Eigen::Matrix3d hc, tf, tt;
    hc << x(0), x(1), x(2), x(3), x(4), x(5), x(6), x(7), 1;
    tf << 1, 0, -of.x(), 0, 1, -of.y(), 0, 0, 1;
    tt << 1, 0, ot.x(), 0, 1, ot.y(), 0, 0, 1;
    Eigen::Matrix3d h = tt * hc * tf;
    if (std::abs(h.determinant()) < 1e-15 * std::pow(h.norm(), 3)) return std::nullopt;
    if (std::abs(h(2, 2)) > 1e-12) h /= h(2, 2);
    return h;
}

}  // namespace

std::optional<Point2> apply_homography(const Eigen::Matrix3d& h, const Point2& p) {
    const Eigen::Vector3d q = h * Eigen::Vector3d(p.x(), p.y(), 1.0);
    if (std::abs(q.z()) < 1e-12) return std::nullopt;
    return Point2(q.x() / q.z(), q.y() / q.z());
}

std::optional<Eigen::Matrix3d> fit_homography(const std::vector<Point2>& from, const std::vector<Point2>& to) {
    const std::size_t n = from.size();
    if (n < 4 || to.size() != n) return std::nullopt;
    const Eigen::Matrix3d tf = normaliser(from), tt = normaliser(to);
    // Accumulate A^T A of the 2n x 9 DLT system; its eigenvector of the
    // smallest eigenvalue is the homography.
    Eigen::Matrix<double, 9, 9> ata = Eigen::Matrix<double, 9, 9>::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d a = tf * Eigen::Vector3d(from[i].x(), from[i].y(), 1.0);
        const Eigen::Vector3d b = tt * Eigen::Vector3d(to[i].x(), to[i].y(), 1.0);
        Eigen::Matrix<double, 9, 1> r1, r2;
        r1 << 0, 0, 0, -b.z() * a.x(), -b.z() * a.y(), -b.z() * a.z(), b.y() * a.x(), b.y() * a.y(), b.y() * a.z();
        r2 << b.z() * a.x(), b.z() * a.y(), b.z() * a.z(), 0, 0, 0, -b.x() * a.x(), -b.x() * a.y(), -b.x() * a.z();
        ata += r1 * r1.transpose() + r2 * r2.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(ata);
    if (eig.info() != Eigen::Success) return std::nullopt;
    // A unique solution has one (near) zero eigenvalue; a second one means the
    // points do not pin the homography down.
    const auto& ev = eig.eigenvalues();
    if (ev(1) <= 1e-9 * std::max(ev(8), 1e-300)) return std::nullopt;
    const Eigen::Matrix<double, 9, 1> v = eig.eigenvectors().col(0);
    Eigen::Matrix3d hn;
    hn << v(0), v(1), v(2), v(3), v(4), v(5), v(6), v(7), v(8);
    Eigen::Matrix3d h = tt.inverse() * hn * tf;
    if (std::abs(h.determinant()) < 1e-15 * std::pow(h.norm(), 3)) return std::nullopt;
    if (std::abs(h(2, 2)) > 1e-12) h /= h(2, 2);
    return h;
}

std::optional<RobustHomography> fit_homography_robust(const std::vector<Point2>& from, const std::vector<Point2>& to,
                                                      double tolerance, int iterations, std::uint64_t seed) {
    const std::size_t n = from.size();
    if (n < 4 || to.size() != n) return std::nullopt;
    std::mt19937_64 rng(seed);
    auto count_inliers = [&](const Eigen::Matrix3d& h, std::vector<bool>& mask) {
        int count = 0;
        mask.assign(n, false);
        for (std::size_t i = 0; i < n; ++i) {
            auto q = apply_homography(h, from[i]);
            if (q && (*q - to[i]).norm() <= tolerance) {
                mask[i] = true;
                ++count;
            }
        }
        return count;
    };
    // Samples are judged on an evenly spread subset of at most kJudges
    // points; only the winner is counted on all of them.
    constexpr std::size_t kJudges = 120;
    const std::size_t stride = std::max<std::size_t>(1, n / kJudges);
    auto judge = [&](const Eigen::Matrix3d& h) {
        int count = 0;
        for (std::size_t i = 0; i < n; i += stride) {
            auto q = apply_homography(h, from[i]);
            count += q && (*q - to[i]).norm() <= tolerance;
        }
        return count;
    };
    RobustHomography best;
    std::vector<bool> mask;
    std::vector<Point2> sf(4), st(4);
    int best_judged = 0;
    const int all_judges = static_cast<int>((n + stride - 1) / stride);
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
        const int c = judge(*h);
        if (c > best_judged) {
            best_judged = c;
            best.h = *h;
            if (c == all_judges) break;
        }
    }
    if (best_judged == 0) return std::nullopt;
    best.inliers = count_inliers(best.h, best.inlier);
    if (best.inliers < 4) return std::nullopt;
    // Refit to every inlier, then take the inliers of the refit.
    for (int round = 0; round < 2; ++round) {
        std::vector<Point2> f, t;
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
