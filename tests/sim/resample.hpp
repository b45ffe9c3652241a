// Perspective sampling of a plane image without aliasing, the way a camera's
// lens and sensor pixels average the light instead of point-sampling it.
//
// Trilinear mipmapping over a 2x supersampled grid: the source is kept at
// halving resolutions; each supersample reads the two levels whose pixels
// best match its footprint (by the footprint's longer side, so strong
// foreshortening blurs a little along the short side rather than alias), and
// 2 x 2 supersamples are averaged into one image pixel like a sensor pixel's
// area. Plain warpPerspective would alias badly once a screen pixel is much
// smaller than an image pixel, producing moire a real camera does not show.
#pragma once

#include <opencv2/core.hpp>

#include <memory>
#include <mutex>
#include <vector>

namespace umf::sim {

// A source (CV_32FC3, linear light) and its halving levels: level 0 is the
// source, each further level the previous one halved (area average). A
// level is made the first time a view needs it and kept, so many views of
// one source pay for the halving once; views on several threads may share
// one. Halving stops before a side would drop below a few pixels.
class Mipmap {
public:
    explicit Mipmap(cv::Mat source);

    int level_count() const { return static_cast<int>(sizes_.size()); }
    cv::Size size(int level) const { return sizes_[static_cast<std::size_t>(level)]; }
    // Level coordinates per source coordinate, in x and y.
    cv::Vec2d scale(int level) const;
    const cv::Mat& level(int level) const;

private:
    std::vector<cv::Size> sizes_;
    mutable std::vector<cv::Mat> levels_;
    std::unique_ptr<std::once_flag[]> made_;
};

// Samples the source (CV_32FC3, linear light) through image_to_source
// (continuous coordinates on both sides: pixel (x, y) covers
// [x, x + 1) x [y, y + 1)). Only the pyramid levels the view needs are built.
// Image points whose ray misses the source plane in front of the camera
// (third homogeneous component <= 0) and points outside the source get
// `outside`. CV_32FC3.
// level_bias > 0 reads finer levels than the footprint asks for, letting
// that many octaves of detail alias: a sensor without an optical low-pass
// filter, which is where moire comes from.
cv::Mat sample_perspective(const Mipmap& source, const cv::Matx33d& image_to_source, cv::Size image,
                           const cv::Vec3f& outside, double level_bias = 0);
cv::Mat sample_perspective(const cv::Mat& source, const cv::Matx33d& image_to_source, cv::Size image,
                           const cv::Vec3f& outside, double level_bias = 0);

}  // namespace umf::sim
