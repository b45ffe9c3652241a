// Accuracy floors per benchmark category on fixed seeds: the first 20 frames
// of each category of tests/bench (the same recipes umf_benchmark uses) at
// opacity 0.3 and 640 x 480, single frames and the tracker. The floors sit a
// little below what this measured; a wrong place is never allowed.
#include <gtest/gtest.h>

#include "bench/scenario.hpp"
#include "detect/tracker.hpp"
#include "field/field_io.hpp"
#include "sim/field_mix.hpp"

namespace {

using namespace umf;

struct Floor {
    bench::Category category;
    int single, video;  // of 20 frames
};

TEST(CategoryFloors, SingleFramesAndTrackerAtOpacity03) {
    const Field f = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const Detector detector(f);
    const bench::Scene scene;
    const sim::FieldPlacement placement{{0, 0}, scene.module_px};
    std::vector<cv::Mat> screens;
    for (auto kind : sim::kAllScreenKinds)
        screens.push_back(sim::mix_field(sim::make_screen(kind, scene.screen.pixels, 7), f, placement, 0.3));
    // Measured: 19, 20, 20, 20, 20, 20, 18 single frames; 20 tracked in every
    // category but low light (19).
    const Floor floors[] = {{bench::Category::near_far, 17, 19},    {bench::Category::horizontal, 18, 19},
                            {bench::Category::rotation, 18, 19},    {bench::Category::perspective, 18, 19},
                            {bench::Category::general, 18, 19},     {bench::Category::occlusion, 18, 19},
                            {bench::Category::low_light, 16, 18}};
    for (const Floor& floor : floors) {
        Tracker tracker(detector);
        int single = 0, video = 0;
        for (const auto& recipe : bench::category_recipes(scene, floor.category, 20, 1)) {
            const bench::Frame frame =
                bench::shoot(scene, recipe, screens[static_cast<std::size_t>(recipe.screen)], {640, 480});
            const GreyView view{frame.grey.data, frame.grey.cols, frame.grey.rows,
                                static_cast<std::ptrdiff_t>(frame.grey.step)};
            auto error = [&](const Eigen::Vector2d& uv) {
                return cv::norm(cv::Point2d(uv.x(), uv.y()) * scene.module_px - frame.centre_screen_px) / scene.module_px;
            };
            const Detection d = detector.detect(view);
            const TrackResult t = tracker.update(view);
            if (!frame.centre_on_screen) continue;
            if (d.found) {
                EXPECT_LT(error(d.aim_field), 1.0) << to_string(floor.category) << " frame " << recipe.index;
                single += error(d.aim_field) < 1.0;
            }
            if (t.state == TrackState::locked) {
                EXPECT_LT(error(t.aim_field), 1.0) << to_string(floor.category) << " frame " << recipe.index;
                video += error(t.aim_field) < 1.0;
            }
        }
        EXPECT_GE(single, floor.single) << to_string(floor.category);
        EXPECT_GE(video, floor.video) << to_string(floor.category);
    }
}

}  // namespace
