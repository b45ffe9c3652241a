#include "tests/sim/curved_motion.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

namespace umf::sim {

cv::Mat curved_motion_kernel(const CurvedBlur& b) {
    const int samples = std::max(2, static_cast<int>(std::ceil(b.length_px * 8)));
    const double a0 = b.start_angle_deg * CV_PI / 180, turn = b.turn_deg * CV_PI / 180;
    // Points along the arc from the origin, then their centre of mass.
    std::vector<cv::Point2d> path;
    cv::Point2d p(0, 0), mean(0, 0);
    const double step = b.length_px / samples;
    for (int i = 0; i < samples; ++i) {
        const double a = a0 + turn * (i + 0.5) / samples;
        p += step * cv::Point2d(std::cos(a), std::sin(a));
        path.push_back(p);
        mean += p;
    }
    mean *= 1.0 / samples;
    double reach = 0;
    for (const auto& q : path) reach = std::max({reach, std::abs(q.x - mean.x), std::abs(q.y - mean.y)});
    const int half = static_cast<int>(std::ceil(reach)) + 1;
    cv::Mat k = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
    for (const auto& q : path) {
        const cv::Point2d at = q - mean + cv::Point2d(half, half);
        const int x = static_cast<int>(std::floor(at.x)), y = static_cast<int>(std::floor(at.y));
        const double fx = at.x - x, fy = at.y - y;
        k.at<float>(y, x) += static_cast<float>((1 - fx) * (1 - fy));
        k.at<float>(y, x + 1) += static_cast<float>(fx * (1 - fy));
        k.at<float>(y + 1, x) += static_cast<float>((1 - fx) * fy);
        k.at<float>(y + 1, x + 1) += static_cast<float>(fx * fy);
    }
    return k / cv::sum(k)[0];
}

void apply_curved_motion(cv::Mat& linear, const CurvedBlur& blur) {
    if (blur.length_px <= 0) return;
    cv::filter2D(linear, linear, -1, curved_motion_kernel(blur), {-1, -1}, 0, cv::BORDER_REFLECT);
}

}  // namespace umf::sim
