#include "tests/sim/resample.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tests/sim/homography.hpp"

namespace umf::sim {
namespace {

constexpr int kSupersample = 2;
constexpr int kMinLevelSide = 4;
// The wanted level varies slowly, so it is computed on a grid of cells this
// many image pixels wide and interpolated.
constexpr int kCell = 4;
constexpr float kNothingShown = -1;
constexpr int kStripRows = 32;  // a multiple of kSupersample

// Largest singular value of a 2x2 matrix: how many source pixels one image
// pixel spans along its footprint's longer axis.
double longer_axis(const cv::Matx22d& j) {
    const double t = j(0, 0) * j(0, 0) + j(0, 1) * j(0, 1) + j(1, 0) * j(1, 0) + j(1, 1) * j(1, 1);
    const double d = j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0);
    return std::sqrt(0.5 * (t + std::sqrt(std::max(0.0, t * t - 4 * d * d))));
}

// Pyramid level (fractional) wanted per grid cell: level L has pixels 2^L
// source pixels wide, and a supersample should span at most one of them.
// Cells that show no source, not even within a cell's footprint, get
// kNothingShown.
cv::Mat wanted_levels(const cv::Matx33d& image_to_source, cv::Size cells, cv::Size source, int level_count,
                      double bias) {
    cv::Mat out(cells, CV_32F);
    for (int y = 0; y < cells.height; ++y) {
        auto* row = out.ptr<float>(y);
        for (int x = 0; x < cells.width; ++x) {
            const cv::Point2d p((x + 0.5) * kCell, (y + 0.5) * kCell);
            const cv::Vec3d q = apply_homogeneous(image_to_source, p);
            if (q[2] <= 0) {
                row[x] = kNothingShown;
                continue;
            }
            const double span = longer_axis(jacobian(image_to_source, p));
            const double margin = 2 * kCell * span;
            const double sx = q[0] / q[2];
            const double sy = q[1] / q[2];
            if (sx < -margin || sy < -margin || sx > source.width + margin || sy > source.height + margin) {
                row[x] = kNothingShown;
                continue;
            }
            row[x] = static_cast<float>(std::clamp(std::log2(std::max(span / kSupersample, 1.0)) - bias, 0.0, level_count - 1.0));
        }
    }
    return out;
}

// The rectangle of supersamples that need `level`: cells whose neighbourhood
// has a wanted level within one of it (the interpolated level there can then
// give this level weight), widened by a cell.
cv::Rect level_area(const cv::Mat& wanted, const cv::Mat& neighbourhood_min, const cv::Mat& neighbourhood_max,
                    int level, cv::Size fine) {
    const cv::Mat needed = (wanted != kNothingShown) & (neighbourhood_min < level + 1) & (neighbourhood_max > level - 1);
    if (cv::countNonZero(needed) == 0) return {};
    cv::Rect cells = cv::boundingRect(needed);
    cells.x -= 1, cells.y -= 1, cells.width += 2, cells.height += 2;
    const int f = kCell * kSupersample;
    return cv::Rect(cells.x * f, cells.y * f, cells.width * f, cells.height * f) & cv::Rect({0, 0}, fine);
}

bool all_in_front(const cv::Matx33d& image_to_source, cv::Size image) {
    for (const cv::Point2d corner : {cv::Point2d(0, 0), cv::Point2d(image.width, 0), cv::Point2d(0, image.height),
                                     cv::Point2d(image.width, image.height)})
        if (apply_homogeneous(image_to_source, corner)[2] <= 0) return false;
    return true;  // the sign is linear in the image point, so corners decide
}

cv::Size halved(cv::Size s) { return {(s.width + 1) / 2, (s.height + 1) / 2}; }

}  // namespace

Mipmap::Mipmap(cv::Mat source) {
    CV_Assert(source.type() == CV_32FC3);
    sizes_.push_back(source.size());
    while (std::min(sizes_.back().width, sizes_.back().height) >= 2 * kMinLevelSide) sizes_.push_back(halved(sizes_.back()));
    levels_.resize(sizes_.size());
    levels_[0] = std::move(source);
    made_ = std::make_unique<std::once_flag[]>(sizes_.size());
}

// resize maps continuous coordinates by the exact size ratio, also for odd sizes.
cv::Vec2d Mipmap::scale(int level) const {
    return {double(size(level).width) / sizes_[0].width, double(size(level).height) / sizes_[0].height};
}

const cv::Mat& Mipmap::level(int level) const {
    const auto i = static_cast<std::size_t>(level);
    if (level > 0)
        std::call_once(made_[i], [&] { cv::resize(this->level(level - 1), levels_[i], sizes_[i], 0, 0, cv::INTER_AREA); });
    return levels_[i];
}

cv::Mat sample_perspective(const cv::Mat& source, const cv::Matx33d& image_to_source, cv::Size image,
                           const cv::Vec3f& outside, double level_bias) {
    return sample_perspective(Mipmap(source), image_to_source, image, outside, level_bias);
}

cv::Mat sample_perspective(const Mipmap& pyramid, const cv::Matx33d& image_to_source, cv::Size image,
                           const cv::Vec3f& outside, double level_bias) {
    const cv::Size source = pyramid.size(0);
    const int level_count = pyramid.level_count();
    const cv::Size cells((image.width + kCell - 1) / kCell, (image.height + kCell - 1) / kCell);
    cv::Mat wanted = wanted_levels(image_to_source, cells, source, level_count, level_bias);

    // Cells showing nothing take the smallest level shown, only so that the
    // interpolation next to them stays in range.
    const cv::Mat shown = wanted != kNothingShown;
    if (cv::countNonZero(shown) == 0) return cv::Mat(image, CV_32FC3, cv::Scalar(outside[0], outside[1], outside[2]));
    double lo = 0;
    double hi = 0;
    cv::minMaxLoc(wanted, &lo, &hi, nullptr, nullptr, shown);
    cv::Mat smooth = wanted.clone();
    smooth.setTo(lo, ~shown);
    cv::Mat neighbourhood_min, neighbourhood_max;
    cv::erode(smooth, neighbourhood_min, cv::Mat(), {-1, -1}, 1, cv::BORDER_REPLICATE);
    cv::dilate(smooth, neighbourhood_max, cv::Mat(), {-1, -1}, 1, cv::BORDER_REPLICATE);

    // Cell centres sit at fine coordinates 8 i + 4, which resize reproduces
    // exactly when the grid is enlarged to whole cells.
    const cv::Size fine(image.width * kSupersample, image.height * kSupersample);
    cv::Mat level_map;
    cv::resize(smooth, level_map, cells * (kCell * kSupersample), 0, 0, cv::INTER_LINEAR);

    // Supersample index -> image continuous -> source continuous.
    const cv::Matx33d fine_to_source =
        image_to_source * scaling(1.0 / kSupersample, 1.0 / kSupersample) * translation(0.5, 0.5);
    const int first_level = static_cast<int>(std::floor(lo));
    const int last_level = std::min(level_count - 1, static_cast<int>(std::ceil(hi)));
    std::vector<cv::Rect> areas;
    for (int level = first_level; level <= last_level; ++level)
        areas.push_back(level_area(wanted, neighbourhood_min, neighbourhood_max, level, fine));

    // One level at full weight everywhere (the common close, square-on
    // view): warp whole strips straight into the sum, no weighting needed.
    const bool single_level = lo == hi && first_level == last_level;

    // Strips of supersample rows small enough to stay in cache: whole
    // supersampled images would be tens of megabytes per level.
    cv::Mat out(image, CV_32FC3);
    cv::Mat sum(kStripRows, fine.width, CV_32FC3);
    cv::Mat weight_sum(kStripRows, fine.width, CV_32F);
    cv::Mat warped;
    const auto warp = [&](int level, cv::Rect area, cv::Mat& dst) {
        const cv::Vec2d s = pyramid.scale(level);
        const cv::Matx33d area_to_level =
            translation(-0.5, -0.5) * scaling(s[0], s[1]) * fine_to_source * translation(area.x, area.y);
        cv::warpPerspective(pyramid.level(level), dst, area_to_level, area.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                            cv::BORDER_CONSTANT, cv::Scalar(outside[0], outside[1], outside[2]));
    };
    for (int top = 0; top < fine.height; top += kStripRows) {
        const cv::Rect strip(0, top, fine.width, std::min(kStripRows, fine.height - top));
        if (single_level) {
            cv::Mat rows = sum.rowRange(0, strip.height);  // warpPerspective writes into it in place
            warp(first_level, strip, rows);
            weight_sum.setTo(cv::Scalar::all(1));
        } else {
            sum.setTo(cv::Scalar::all(0));
            weight_sum.setTo(cv::Scalar::all(0));
            for (int level = first_level; level <= last_level; ++level) {
                const cv::Rect area = areas[level - first_level] & strip;
                if (area.empty()) continue;
                warp(level, area, warped);
                for (int y = 0; y < area.height; ++y) {
                    const auto* l = level_map.ptr<float>(area.y + y) + area.x;
                    const auto* w = warped.ptr<cv::Vec3f>(y);
                    auto* o = sum.ptr<cv::Vec3f>(area.y - top + y) + area.x;
                    auto* ws = weight_sum.ptr<float>(area.y - top + y) + area.x;
                    for (int x = 0; x < area.width; ++x) {
                        const float weight = 1.0f - std::abs(l[x] - static_cast<float>(level));
                        if (weight <= 0) continue;
                        o[x] += weight * w[x];
                        ws[x] += weight;
                    }
                }
            }
        }
        // Supersamples no level covered show `outside`; 2 x 2 supersamples
        // average into one image pixel, as light does over a sensor pixel.
        for (int y = 0; y < strip.height / kSupersample; ++y) {
            auto* o = out.ptr<cv::Vec3f>(top / kSupersample + y);
            for (int x = 0; x < image.width; ++x) {
                cv::Vec3f acc(0, 0, 0);
                for (int dy = 0; dy < kSupersample; ++dy) {
                    const auto* srow = sum.ptr<cv::Vec3f>(kSupersample * y + dy);
                    const auto* wrow = weight_sum.ptr<float>(kSupersample * y + dy);
                    for (int dx = 0; dx < kSupersample; ++dx) {
                        const int fx = kSupersample * x + dx;
                        acc += srow[fx] + std::max(0.0f, 1 - wrow[fx]) * outside;
                    }
                }
                o[x] = acc * (1.0f / (kSupersample * kSupersample));
            }
        }
    }

    // Behind the camera the homography folds the plane back into view; blank it.
    if (!all_in_front(image_to_source, image))
        for (int y = 0; y < image.height; ++y) {
            auto* o = out.ptr<cv::Vec3f>(y);
            for (int x = 0; x < image.width; ++x)
                if (apply_homogeneous(image_to_source, {x + 0.5, y + 0.5})[2] <= 0) o[x] = outside;
        }
    return out;
}

}  // namespace umf::sim
