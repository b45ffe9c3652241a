// Small helpers for 3x3 homographies acting on continuous pixel coordinates.
#pragma once

#include <opencv2/core.hpp>

namespace umf::sim {

// The homogeneous image of p, not divided: its third component tells on
// which side of the camera a plane point lies (see camera.cpp).
inline cv::Vec3d apply_homogeneous(const cv::Matx33d& h, cv::Point2d p) { return h * cv::Vec3d(p.x, p.y, 1.0); }

inline cv::Point2d apply(const cv::Matx33d& h, cv::Point2d p) {
    const cv::Vec3d q = apply_homogeneous(h, p);
    return {q[0] / q[2], q[1] / q[2]};
}

// d(output)/d(input) at p: columns are the images of unit steps in x and y.
inline cv::Matx22d jacobian(const cv::Matx33d& h, cv::Point2d p) {
    const cv::Vec3d q = apply_homogeneous(h, p);
    const double x = q[0] / q[2];
    const double y = q[1] / q[2];
    return cv::Matx22d(h(0, 0) - x * h(2, 0), h(0, 1) - x * h(2, 1),  //
                       h(1, 0) - y * h(2, 0), h(1, 1) - y * h(2, 1)) *
           (1.0 / q[2]);
}

inline cv::Matx33d translation(double dx, double dy) { return {1, 0, dx, 0, 1, dy, 0, 0, 1}; }
inline cv::Matx33d scaling(double sx, double sy) { return {sx, 0, 0, 0, sy, 0, 0, 0, 1}; }

}  // namespace umf::sim
