// Which of a scan's edgels the detector searches first (Detector's
// search_edgel_sets): the field's own, those stepping by the commonest edge
// step. Over a screen's content, all edgels' lines are often the content's,
// and every wrong grid read costs as much as the right one.
#include <gtest/gtest.h>

#include "shared/detect/detector.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/heldout_run.hpp"
#include "tests/bench/heldout_scenario.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/heldout_content.hpp"

namespace {

using namespace umf;

// The held-out set's moving and turned views (its screens and contents
// as the recipes pick them) at 640 x 480, the field at opacity 0.3:
// searched with all edgels first, 3 of 20 were found on the first grid
// read; with the field-like edgels first, 16.
TEST(DetectorEdgelSets, TheFieldsOwnEdgelsFindItOnTheFirstGrid) {
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const Detector detector(field);
    const cv::Size modules(field.width, field.height);
    const auto& screens = bench::heldout_screens();
    int found = 0, first_grid = 0, frames = 0;
    for (const auto category : {bench::HeldoutCategory::motion, bench::HeldoutCategory::rotation}) {
        for (const auto& r : bench::heldout_recipes(category, 10, 1)) {
            const auto& screen = screens[static_cast<std::size_t>(r.screen)];
            const sim::FieldPlacement placement = bench::heldout_placement(screen, field);
            const cv::Mat content = sim::make_heldout_screen(r.content, screen.geometry.pixels, bench::kHeldoutScreenSeed);
            const bench::Frame frame = bench::shoot_heldout(r, sim::mix_field(content, field, placement, 0.3),
                                                            cv::Size(640, 480), placement, modules);
            const GreyView v{frame.grey.data, frame.grey.cols, frame.grey.rows,
                             static_cast<std::ptrdiff_t>(frame.grey.step)};
            const Detection d = detector.detect(v);
            ++frames;
            found += d.found;
            first_grid += d.found && d.grids_read == 1;
        }
    }
    EXPECT_GE(found, 19) << "of " << frames;
    EXPECT_GE(first_grid, 13) << "found on the first grid read, of " << frames;
}

}  // namespace
