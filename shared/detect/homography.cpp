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
    RobustHomography best;
    std::vector<bool> mask;
    std::vector<Point2> sf(4), st(4);
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
        auto h = fit_homography(sf, st);
        if (!h) continue;
        const int c = count_inliers(*h, mask);
        if (c > best.inliers) {
            best.h = *h;
            best.inliers = c;
            best.inlier = mask;
            if (static_cast<std::size_t>(c) == n) break;
        }
    }
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
