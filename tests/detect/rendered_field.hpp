// A field rendered through a known homography, for the tests of the steps
// that fit one to the image (refine.hpp, module_centring.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "shared/detect/homography.hpp"
#include "shared/detect/module_edges.hpp"
#include "shared/field/field.hpp"

namespace umf::test {

// The field seen through `field_to_image`, each pixel the mean of 4 x 4
// samples, blurred as a camera's optics do, faint (24 grey levels between
// the darkest and brightest module) over mid-grey, with noise.
inline cv::Mat render_field(const Field& f, const Eigen::Matrix3d& field_to_image, cv::Size size, double blur_px) {
    const std::vector<double> b = module_brightness(f);
    const auto [lo, hi] = std::minmax_element(b.begin(), b.end());
    const Eigen::Matrix3d to_field = field_to_image.inverse();
    cv::Mat out(size, CV_8UC1);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            double sum = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const auto q = apply_homography(to_field, Point2(x + (sx + 0.5) / 4, y + (sy + 0.5) / 4));
                    double level = 0.5;
                    if (q && q->x() >= 0 && q->y() >= 0 && q->x() < f.width && q->y() < f.height)
                        level = (b[f.at(static_cast<int>(q->y()), static_cast<int>(q->x()))] - *lo) / (*hi - *lo);
                    sum += level;
                }
            out.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(116 + 24 * sum / 16);
        }
    cv::GaussianBlur(out, out, cv::Size(), blur_px);
    cv::Mat noise(size, CV_16SC1);
    cv::RNG rng(5);
    rng.fill(noise, cv::RNG::NORMAL, 0, 2);
    cv::Mat grey;
    out.convertTo(grey, CV_16SC1);
    grey += noise;
    grey.convertTo(out, CV_8UC1);
    return out;
}

// A field seen at an angle: `module_px` pixels a module at the field point
// (24, 14), which lands at the image's centre.
inline Eigen::Matrix3d seen_at_an_angle(double module_px, cv::Size size) {
    Eigen::Matrix3d h;
    h << module_px, 0.12 * module_px, 0, -0.08 * module_px, 0.95 * module_px, 0, 0.004, 0.002, 1;
    // Move the field point (24, 14) to the image centre.
    const Point2 at = *apply_homography(h, Point2(24, 14));
    Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
    shift(0, 2) = size.width / 2.0 - at.x();
    shift(1, 2) = size.height / 2.0 - at.y();
    return shift * h;
}

// How far (modules) the image centre lands from where it truly is.
inline double aim_error(const Eigen::Matrix3d& truth, const Eigen::Matrix3d& fitted, cv::Size size) {
    const Point2 centre(size.width / 2.0, size.height / 2.0);
    return (*apply_homography(fitted.inverse(), centre) - *apply_homography(truth.inverse(), centre)).norm();
}

}  // namespace umf::test
