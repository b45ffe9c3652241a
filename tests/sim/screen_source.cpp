#include "tests/sim/screen_source.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "tests/sim/homography.hpp"

namespace umf::sim {
namespace {

// A thin black bezel around the screen gives the detector the real-world
// distraction of a strong dark frame.
constexpr double kBezelMm = 8;
const cv::Vec3b kBezelBgr(18, 18, 18);

cv::Mat pad(const cv::Mat& image, int left_right, int top_bottom, const cv::Scalar& value) {
    cv::Mat out;
    cv::copyMakeBorder(image, out, top_bottom, top_bottom, left_right, left_right, cv::BORDER_CONSTANT, value);
    return out;
}

// With subpixels the source is the striped screen, three times as wide, and
// with the grid three times as tall too, so that the sampling averages real
// stripes, as the camera's pixels do.
ScreenSource::Light make_light(const cv::Mat& bgr, int bezel_px, ScreenRendering rendering) {
    const cv::Scalar bezel(to_linear(kBezelBgr));
    switch (rendering) {
    case ScreenRendering::pixel_grid:
        return {Mipmap(pad(pixel_grid(to_linear(bgr)), 3 * bezel_px, 3 * bezel_px, bezel)),
                scaling(3, 3) * translation(bezel_px, bezel_px)};
    case ScreenRendering::subpixels:
        return {Mipmap(pad(subpixel_stripes(to_linear(bgr)), 3 * bezel_px, bezel_px, bezel)),
                scaling(3, 1) * translation(bezel_px, bezel_px)};
    case ScreenRendering::plain:
        break;
    }
    return {Mipmap(to_linear(pad(bgr, bezel_px, bezel_px, cv::Scalar(kBezelBgr)))), translation(bezel_px, bezel_px)};
}

}  // namespace

ScreenRendering rendering_for(const Degradation& d) {
    return d.pixel_grid ? ScreenRendering::pixel_grid : d.subpixels ? ScreenRendering::subpixels : ScreenRendering::plain;
}

ScreenSource::ScreenSource(cv::Mat screen_bgr, const ScreenGeometry& screen)
    : bgr_(std::move(screen_bgr)),
      screen_(screen),
      bezel_px_(static_cast<int>(std::lround(kBezelMm / screen_mm_per_px(screen)))),
      made_(std::make_unique<std::once_flag[]>(kScreenRenderings)) {
    CV_Assert(bgr_.type() == CV_8UC3 && bgr_.size() == screen.pixels);
}

const ScreenSource::Light& ScreenSource::light(ScreenRendering rendering) const {
    const auto i = static_cast<std::size_t>(rendering);
    std::call_once(made_[i], [&] { lights_[i] = std::make_unique<Light>(make_light(bgr_, bezel_px_, rendering)); });
    return *lights_[i];
}

std::vector<ScreenSource> screen_sources(const std::vector<cv::Mat>& screens, const ScreenGeometry& geometry) {
    std::vector<ScreenSource> out;
    out.reserve(screens.size());
    for (const cv::Mat& s : screens) out.emplace_back(s, geometry);
    return out;
}

}  // namespace umf::sim
