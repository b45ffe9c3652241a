// Accuracy floors per benchmark category on fixed seeds: the first 20 frames
// of each category of tests/bench (the same recipes umf_benchmark uses) at
// opacity 0.3 and 640 x 480, single frames and the tracker. The floors sit a
// little below what this measured; a wrong place (more than half a module
// from the truth) is never allowed.
#include <gtest/gtest.h>

#include <iostream>

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
    // Measured at half a module: 19, 20, 20, 20, 20, 20, 19, 17, 20, 20 single
    // frames; 20 tracked in every category but smeared (18).
    const Floor floors[] = {{bench::Category::near_far, 18, 19},   {bench::Category::horizontal, 19, 19},
                            {bench::Category::rotation, 19, 19},   {bench::Category::perspective, 19, 19},
                            {bench::Category::general, 19, 19},    {bench::Category::occlusion, 19, 19},
                            {bench::Category::low_light, 17, 19},  {bench::Category::smeared, 15, 16},
                            {bench::Category::distant, 18, 19},    {bench::Category::compressed, 18, 19}};
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
                EXPECT_LT(error(d.aim_field), 0.5) << to_string(floor.category) << " frame " << recipe.index;
                single += error(d.aim_field) < 0.5;
            }
            if (t.state == TrackState::locked) {
                EXPECT_LT(error(t.aim_field), 0.5) << to_string(floor.category) << " frame " << recipe.index;
                video += error(t.aim_field) < 0.5;
            }
        }
        std::cout << to_string(floor.category) << ": " << single << " single, " << video << " tracked\n";
        EXPECT_GE(single, floor.single) << to_string(floor.category);
        EXPECT_GE(video, floor.video) << to_string(floor.category);
    }
}

}  // namespace
