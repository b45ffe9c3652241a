// A screen made ready once (ScreenSource) must photograph exactly as the
// screen given afresh to every shot does: the tests and benchmarks that
// reuse one for speed keep their frames, and so their measured figures.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <thread>
#include <vector>

#include "tests/sim/camera.hpp"
#include "tests/sim/screen_content.hpp"
#include "tests/sim/screen_source.hpp"

namespace {

using namespace umf::sim;

const ScreenGeometry kSourceScreen{{1920, 1080}, 527};
const CameraModel kSourceCamera{{320, 240}, 65};

// Near and square-on (the finest level), far and steep (several levels
// blended), and one looking partly past the screen's edge.
std::vector<CameraPose> poses() {
    std::vector<CameraPose> out(3);
    out[0].aim_screen_px = {700, 400};
    out[0].distance_mm = 150;
    out[1].aim_screen_px = {960, 540};
    out[1].distance_mm = 900;
    out[1].pitch_deg = 50;
    out[1].roll_deg = 20;
    out[2].aim_screen_px = {1850, 60};
    out[2].distance_mm = 400;
    out[2].yaw_deg = -35;
    return out;
}

Degradation rendered(ScreenRendering rendering) {
    Degradation d;
    d.subpixels = rendering == ScreenRendering::subpixels;
    d.pixel_grid = rendering == ScreenRendering::pixel_grid;
    d.noise_sigma = 2;
    d.seed = 5;
    return d;
}

bool same(const cv::Mat& a, const cv::Mat& b) { return a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0; }

TEST(ScreenSource, ShotsFromOneSourceAreTheShotsOfTheScreenGivenAfresh) {
    const cv::Mat screen = make_screen(ScreenKind::web_page, kSourceScreen.pixels, 3);
    const ScreenSource source(screen, kSourceScreen);
    for (const auto rendering : {ScreenRendering::plain, ScreenRendering::subpixels, ScreenRendering::pixel_grid})
        for (const CameraPose& pose : poses()) {
            const Degradation d = rendered(rendering);
            const Shot afresh = photograph(screen, kSourceScreen, kSourceCamera, pose, d, 20);
            const Shot reused = photograph(source, kSourceCamera, pose, d, 20);
            EXPECT_TRUE(same(afresh.bgr, reused.bgr)) << "rendering " << static_cast<int>(rendering);
            EXPECT_EQ(afresh.image_to_screen, reused.image_to_screen);
            EXPECT_EQ(afresh.module_px_in_image, reused.module_px_in_image);
        }
}

TEST(ScreenSource, ShotsOnSeveralThreadsShareOneSource) {
    const cv::Mat screen = make_screen(ScreenKind::document, kSourceScreen.pixels, 4);
    const ScreenSource source(screen, kSourceScreen);
    const std::vector<CameraPose> views = poses();
    std::vector<Shot> shots(views.size());
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < views.size(); ++i)
        threads.emplace_back([&, i] { shots[i] = photograph(source, kSourceCamera, views[i], rendered(ScreenRendering::plain)); });
    for (auto& t : threads) t.join();
    for (std::size_t i = 0; i < views.size(); ++i)
        EXPECT_TRUE(same(shots[i].bgr, photograph(screen, kSourceScreen, kSourceCamera, views[i], rendered(ScreenRendering::plain)).bgr))
            << "view " << i;
}

TEST(ScreenSource, RefusesAScreenOfAnotherSize) {
    EXPECT_THROW(ScreenSource(cv::Mat(100, 100, CV_8UC3), kSourceScreen), cv::Exception);
}

}  // namespace
