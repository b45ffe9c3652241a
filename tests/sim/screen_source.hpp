// The screen as photograph()'s light source: in linear light with its thin
// black bezel, in the rendering a shot asks for (plain pixels, subpixel
// stripes, the pixel grid), mipmapped for antialiased sampling.
//
// Converting a full-HD screen to linear light and halving it costs several
// times what sampling one 640 x 480 view of it does, so a test or benchmark
// that photographs one screen many times makes its ScreenSource once. Each
// rendering and each of its levels is made the first time a shot needs it
// and kept; shots on several threads may share one. Memory: about 26 MB of
// floats for a full-HD screen, three times that with subpixels and nine
// times with the pixel grid, a third more for the levels.
#pragma once

#include <opencv2/core.hpp>

#include <memory>
#include <mutex>
#include <vector>

#include "tests/sim/camera.hpp"
#include "tests/sim/resample.hpp"

namespace umf::sim {

enum class ScreenRendering { plain, subpixels, pixel_grid };
inline constexpr std::size_t kScreenRenderings = 3;

ScreenRendering rendering_for(const Degradation& degradation);

class ScreenSource {
public:
    // screen_bgr: CV_8UC3 of screen.pixels' size; kept, not copied.
    ScreenSource(cv::Mat screen_bgr, const ScreenGeometry& screen);

    const ScreenGeometry& geometry() const { return screen_; }

    struct Light {
        Mipmap mipmap;
        cv::Matx33d from_screen;  // screen coordinates -> the rendering's pixel coordinates
    };
    const Light& light(ScreenRendering rendering) const;

private:
    cv::Mat bgr_;
    ScreenGeometry screen_;
    int bezel_px_ = 0;
    mutable std::unique_ptr<Light> lights_[kScreenRenderings];
    std::unique_ptr<std::once_flag[]> made_;
};

// One source per screen, all of one geometry (cheap: nothing is made until a
// shot needs it).
std::vector<ScreenSource> screen_sources(const std::vector<cv::Mat>& screens, const ScreenGeometry& geometry);

}  // namespace umf::sim
