#include "shared/detect/pulse_course.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace umf {

PulseCourse find_pulse_course(std::span<const GreyView> frames, int sample_step) {
    PulseCourse out;
    const int n = static_cast<int>(frames.size());
    if (n < 3 || sample_step < 1) return out;
    for (const GreyView& f : frames)
        if (!describe_invalid(f).empty() || f.width != frames[0].width || f.height != frames[0].height) return out;
    // The sampled pixels of every frame less their mean over the frames.
    const int w = frames[0].width, h = frames[0].height;
    const int cols = (w + sample_step - 1) / sample_step, rows = (h + sample_step - 1) / sample_step;
    Eigen::MatrixXd centred(n, static_cast<Eigen::Index>(cols) * rows);
    for (int y = 0, j = 0; y < h; y += sample_step)
        for (int x = 0; x < w; x += sample_step, ++j)
            for (int i = 0; i < n; ++i) centred(i, j) = frames[static_cast<std::size_t>(i)].at(x, y);
    centred.rowwise() -= centred.colwise().mean();
    const Eigen::MatrixXd covariance = centred * centred.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
    if (eigen.info() != Eigen::Success) return out;
    const double total = covariance.trace();
    if (!(total > 0)) return out;
    // Eigenvalues come in increasing order: the last is the leading one.
    Eigen::VectorXd course = eigen.eigenvectors().col(n - 1);
    course.array() -= course.mean();
    const double largest = course.cwiseAbs().maxCoeff();
    if (!(largest > 0)) return out;
    out.level.assign(course.data(), course.data() + n);
    for (double& v : out.level) v /= largest;
    out.covariance = covariance;
    out.share = std::clamp(eigen.eigenvalues()(n - 1) / total, 0.0, 1.0);
    return out;
}

}  // namespace umf
