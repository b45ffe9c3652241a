// Accuracy floors per benchmark category on fixed seeds: the first 20 frames
// of each category of tests/bench (the same recipes umf_benchmark uses) at
// opacity 0.3 and 640 x 480, single frames and the tracker. The floors sit a
// little below what this measured; a wrong place (more than half a module
// from the truth) is never allowed.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>

#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"

namespace {

using namespace umf;

// The benchmark's scenes: its field mixed into every screen.
struct Scenes {
    Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    bench::Scene scene;
    std::vector<sim::ScreenSource> screens;

    explicit Scenes(double opacity = 0.3) {
        const sim::FieldPlacement placement{{0, 0}, scene.module_px};
        for (auto kind : sim::kAllScreenKinds)
            screens.emplace_back(sim::mix_field(sim::make_screen(kind, scene.screen.pixels, 7), field, placement, opacity),
                                 scene.screen);
    }
    bench::Frame shoot(const bench::FrameRecipe& recipe, cv::Size resolution) const {
        return bench::shoot(scene, recipe, screens[static_cast<std::size_t>(recipe.screen)], resolution);
    }
    // Modules from the truth under the frame's centre to a reported point.
    double error(const bench::Frame& frame, const Eigen::Vector2d& uv) const {
        return cv::norm(cv::Point2d(uv.x(), uv.y()) * scene.module_px - frame.centre_screen_px) / scene.module_px;
    }
};

GreyView view_of(const cv::Mat& grey) {
    return {grey.data, grey.cols, grey.rows, static_cast<std::ptrdiff_t>(grey.step)};
}

struct Floor {
    bench::Category category;
    int single, video;  // of 20 frames
};

TEST(CategoryFloors, SingleFramesAndTrackerAtOpacity03) {
    const Scenes scenes;
    const Detector detector(scenes.field);
    // Measured at half a module: 20 single frames in every category but
    // tiny (19, 17 before the lattice); 20 tracked in every category. A
    // spreadsheet (ruled) is no harder than other screens at this opacity.
    // The third camera model (sensor): 19 single, 20 tracked.
    const Floor floors[] = {{bench::Category::near_far, 18, 19},   {bench::Category::horizontal, 19, 19},
                            {bench::Category::rotation, 19, 19},   {bench::Category::perspective, 19, 19},
                            {bench::Category::general, 19, 19},    {bench::Category::occlusion, 19, 19},
                            {bench::Category::low_light, 17, 19},  {bench::Category::smeared, 17, 18},
                            {bench::Category::distant, 18, 19},    {bench::Category::compressed, 18, 19},
                            {bench::Category::tiny, 17, 19},       {bench::Category::pixel_grid, 19, 19},
                            {bench::Category::ruled, 19, 19},      {bench::Category::sensor, 18, 19}};
    for (const Floor& floor : floors) {
        Tracker tracker(detector);
        int single = 0, video = 0;
        for (const auto& recipe : bench::category_recipes(scenes.scene, floor.category, 20, 1)) {
            const bench::Frame frame = scenes.shoot(recipe, {640, 480});
            const GreyView view = view_of(frame.grey);
            auto error = [&](const Eigen::Vector2d& uv) { return scenes.error(frame, uv); };
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

struct FoundAtSize {
    int found = 0;             // within half a module of the truth
    int found_elsewhere = 0;   // of them, at another size than the frame's
    int found_at_own_size = 0; // by a detector that searches the frame's own size alone
};

// The first `frames` frames of a category at opacity 0.3, each on its own.
// A map found at another size, scaled back to the frame, must take the aim
// to the point it reports.
FoundAtSize find_at_sizes(bench::Category category, int frames, cv::Size resolution,
                          const DetectorOptions& options = {}) {
    const Scenes scenes;
    const Detector detector(scenes.field, options);
    DetectorOptions own_size_only = options;
    own_size_only.half_size_min_side = 0;
    own_size_only.double_size_max_side = 0;
    own_size_only.lattice_enabled = false;
    own_size_only.smoothed_search = false;
    const Detector at_own_size(scenes.field, own_size_only);
    FoundAtSize out;
    for (const auto& recipe : bench::category_recipes(scenes.scene, category, frames, 1)) {
        const bench::Frame frame = scenes.shoot(recipe, resolution);
        if (!frame.centre_on_screen) continue;
        const GreyView view = view_of(frame.grey);
        const Detection d = detector.detect(view);
        out.found_at_own_size += at_own_size.detect(view).found;
        if (!d.found) continue;
        const double error = scenes.error(frame, d.aim_field);
        EXPECT_LT(error, 0.5) << "frame " << recipe.index;
        out.found += error < 0.5;
        if (d.size_scale == 1) continue;
        ++out.found_elsewhere;
        const Eigen::Vector3d at_aim = d.image_to_field * Eigen::Vector3d(d.aim_image.x(), d.aim_image.y(), 1);
        EXPECT_LT((at_aim.hnormalized() - d.aim_field).norm(), 0.25) << "frame " << recipe.index;
    }
    std::cout << to_string(category) << " at " << resolution.width << " x " << resolution.height << ": " << out.found
              << " found, " << out.found_elsewhere << " of them at another size; " << out.found_at_own_size
              << " at the frame's own size alone\n";
    return out;
}

// The smear grows with the sensor: 12-36 px at 1920 x 1080, where a
// module's edge spreads over more pixels than the edgels take in. The
// search at half size finds them.
TEST(CategoryFloors, SmearedFullHdFramesAreFoundAtHalfSize) {
    const FoundAtSize r = find_at_sizes(bench::Category::smeared, 12, {1920, 1080});
    // Measured: 12 found, 3 of them at half size (9 at full size alone).
    EXPECT_GE(r.found, 11);
    EXPECT_GE(r.found_elsewhere, 2);
}

// Modules of 3-4 pixels: a grid line's module edges lie closer than the
// edgels and gradients reach. The search at double size (of the middle
// of the frame) finds them. There the corners of such modules are rounded
// and their edges' gradients stray from the grid's directions: the
// vanishing points take edgels up to 25 degrees off (15 elsewhere). The
// lattice (tried before double size, and finding most of these) is left
// out here, so that double size shows on its own.
TEST(CategoryFloors, TinyModulesAreFoundAtDoubleSize) {
    DetectorOptions no_lattice;
    no_lattice.lattice_enabled = false;
    const FoundAtSize r = find_at_sizes(bench::Category::tiny, 20, {640, 480}, no_lattice);
    // Measured: 17 found, 14 of them at another size than the frame's.
    EXPECT_GE(r.found, 15);
    EXPECT_GE(r.found_elsewhere, 7);
    DetectorOptions narrow = no_lattice;
    narrow.double_size_max_inlier_deg = 15;
    const FoundAtSize strict = find_at_sizes(bench::Category::tiny, 20, {640, 480}, narrow);
    // Measured: 13 found at another size with 15 degrees at double size,
    // 14 with 25 (6 and 9 while the refit fitted module edges as points).
    EXPECT_GE(r.found_elsewhere, strict.found_elsewhere + 1);
}

// The first `frames` frames of a category at `resolution` and `opacity`, each on its
// own, by the default detector and by one with `variant` options: how many
// each placed within half a module of the truth (a wrong place fails the
// test), and how many of the default's were found on a lattice.
struct AgainstVariant {
    int found = 0, found_variant = 0, on_lattice = 0;
};

AgainstVariant against_variant(bench::Category category, double opacity, const DetectorOptions& variant,
                               cv::Size resolution = {640, 480}, int frames = 20, const DetectorOptions& base = {}) {
    const Scenes scenes(opacity);
    const Detector detector(scenes.field, base), other(scenes.field, variant);
    AgainstVariant out;
    for (const auto& recipe : bench::category_recipes(scenes.scene, category, frames, 1)) {
        const bench::Frame frame = scenes.shoot(recipe, resolution);
        if (!frame.centre_on_screen) continue;
        const GreyView view = view_of(frame.grey);
        for (auto [d, count] : {std::pair{detector.detect(view), &out.found}, {other.detect(view), &out.found_variant}}) {
            if (!d.found) continue;
            const double error = scenes.error(frame, d.aim_field);
            EXPECT_LT(error, 0.5) << to_string(category) << " frame " << recipe.index;
            *count += error < 0.5;
            out.on_lattice += count == &out.found && error < 0.5 && d.from_lattice;
        }
    }
    return out;
}

// A dim room and a faint field (low light at opacity 0.15): when the first
// scans find nothing in a noisy frame, the scans three pixels wide with a
// lower bar for edges find the field's faint edges. (Both without the
// lattice at smaller sizes, which finds most of the same frames otherwise.)
TEST(CategoryFloors, DimFaintFramesAreFoundWithALowerEdgeBar) {
    DetectorOptions base;
    base.lattice_sizes = 0;
    DetectorOptions strict_bar = base;
    strict_bar.noisy_edge_deviations = 4.5;  // as high as the first scans'
    const AgainstVariant r =
        against_variant(bench::Category::low_light, 0.15, strict_bar, {640, 480}, 20, base);
    std::cout << "low light at opacity 0.15: " << r.found << " found, " << r.found_variant
              << " with the first scans' bar\n";
    // Measured: 20 found, 17 with the first scans' bar.
    EXPECT_GE(r.found, 15);
    EXPECT_GE(r.found, r.found_variant + 2);
}

// A faint field over a spreadsheet (ruled at opacity 0.08, 1280 x 720): the
// sheet's rules run with the field's lines and outweigh its edges, so the
// grid lines found are the sheet's; searched again without the thin lines
// among the edgels, the field's own lines come through.
TEST(CategoryFloors, FaintFieldsOverASpreadsheetAreFoundWithoutItsRules) {
    DetectorOptions with_rules;
    with_rules.thin_line_px = 0;
    const AgainstVariant r = against_variant(bench::Category::ruled, 0.08, with_rules, {1280, 720}, 40);
    std::cout << "ruled at opacity 0.08, 1280 x 720: " << r.found << " found, " << r.found_variant
              << " with the rules\n";
    // Measured over 40 frames: 28 found, 27 with the rules (23 and 19 while
    // the refit fitted module edges as points: refits that converge now
    // place the field on the sheet's grid lines as well, most of the time).
    EXPECT_GE(r.found, 25);
    EXPECT_GE(r.found, r.found_variant + 1);
}

// A faint field through the third camera model (sensor at opacity 0.08,
// 1280 x 720): the screen's colour stripes under a scaler that skips
// photosites fold into a hatch of 2-5 px whose edges pull the grid's
// directions to their own; on the frame smoothed the field's edges come
// through.
TEST(CategoryFloors, FaintFieldsUnderAHatchAreFoundOnTheFrameSmoothed) {
    DetectorOptions sharp_only;
    sharp_only.smoothed_search = false;
    const AgainstVariant r = against_variant(bench::Category::sensor, 0.08, sharp_only, {1280, 720}, 40);
    std::cout << "sensor at opacity 0.08, 1280 x 720: " << r.found << " found, " << r.found_variant
              << " without the smoothed frame\n";
    // Measured over 40 frames: 36 found, 33 without the smoothed frame.
    EXPECT_GE(r.found, 34);
    EXPECT_GE(r.found, r.found_variant + 2);
}

// Modules of 3-4 pixels in a faint field (tiny at opacity 0.15): where the
// frame's own size and smaller ones do not find the grid's directions, the
// lattice the spectrum of edge strength shows around the aim (lattice.hpp)
// does.
TEST(CategoryFloors, TinyFaintModulesAreFoundOnALattice) {
    DetectorOptions no_lattice;
    no_lattice.lattice_enabled = false;
    const AgainstVariant r = against_variant(bench::Category::tiny, 0.15, no_lattice);
    std::cout << "tiny at opacity 0.15: " << r.found << " found, " << r.on_lattice << " of them on a lattice; "
              << r.found_variant << " without the lattice\n";
    // Measured: 15 found, 10 of them on a lattice; 9 without the lattice
    // (which finds some of them at double size).
    EXPECT_GE(r.found, 13);
    EXPECT_GE(r.on_lattice, 8);
    EXPECT_GE(r.found, r.found_variant + 4);
}

// A dim room and a very faint field (low light at opacity 0.06, 1280 x 720):
// the modules' edges are too weak and too noisy for the edgels' directions
// at any size, but over a patch of a few dozen modules at a quarter or half
// size their spectrum (the lattice) still shows the grid.
TEST(CategoryFloors, DimFaintFieldsAreFoundOnALatticeAtASmallerSize) {
    DetectorOptions own_size_only;
    own_size_only.lattice_sizes = 0;
    const AgainstVariant r = against_variant(bench::Category::low_light, 0.06, own_size_only, {1280, 720}, 40);
    std::cout << "low light at opacity 0.06, 1280 x 720: " << r.found << " found, " << r.on_lattice
              << " of them on a lattice; " << r.found_variant << " with the lattice at the frame's own size only\n";
    // Measured over 40 frames: 28 found, 7 of them on a lattice; 23 with the
    // lattice at the frame's own size only.
    EXPECT_GE(r.found, 26);
    EXPECT_GE(r.on_lattice, 5);
    EXPECT_GE(r.found, r.found_variant + 3);
}

// Four tuning frames whose place passed the checks about half a module off
// at the aim: the refit around the aim, its edge searches falling between
// each edge and its neighbour, ended 0.5-0.65 module off. It fitted less
// than 0.9 of the edges it found, ran again from the module centring
// (module_centring.hpp), and that refit, fitting 0.9 of its edges and more
// than the first, places the aim.
TEST(CategoryFloors, AimsReadHalfAModuleOffAreCentredAgain) {
    struct Case {
        bench::Category category;
        int index;
        double opacity;
        cv::Size resolution;
    };
    DetectorOptions never_again;
    never_again.aim_refit_min_share = 0;
    int off_without = 0;
    for (const Case& c : {Case{bench::Category::near_far, 2, 0.2, {640, 480}},
                          Case{bench::Category::pixel_grid, 38, 0.2, {640, 480}},
                          Case{bench::Category::smeared, 2, 0.2, {640, 480}},
                          Case{bench::Category::ruled, 18, 0.15, {1280, 720}}}) {
        const Scenes scenes(c.opacity);
        const bench::FrameRecipe recipe =
            bench::category_recipes(scenes.scene, c.category, 40, 1).at(static_cast<std::size_t>(c.index));
        const bench::Frame frame = scenes.shoot(recipe, c.resolution);
        const Detection d = Detector(scenes.field).detect(view_of(frame.grey));
        const Detection without = Detector(scenes.field, never_again).detect(view_of(frame.grey));
        ASSERT_TRUE(d.found && without.found) << to_string(c.category) << " frame " << c.index;
        std::cout << to_string(c.category) << " frame " << c.index << ": " << scenes.error(frame, d.aim_field)
                  << " module off, " << scenes.error(frame, without.aim_field) << " without the centring\n";
        EXPECT_LT(scenes.error(frame, d.aim_field), 0.2) << to_string(c.category) << " frame " << c.index;
        off_without += scenes.error(frame, without.aim_field) > 0.45;
    }
    // Measured: 0.01-0.05 module off; without, 0.52-0.65 in all four.
    EXPECT_GE(off_without, 3);
}

}  // namespace

namespace {

// A search tries its likeliest pairs of grid-line labellings first; a
// failing one goes on through every pair, 15 to 27 of them. The first pass
// gives every search (each scan, each size, the lattice) its first nine
// pairs, the second pass the rest: the frames are found as by one pass, and
// those found by a later search cost fewer grids read on the way.
TEST(CategoryFloors, TwoPassesFindWhatOnePassFindsReadingFewerGrids) {
    const Scenes scenes(0.3);
    DetectorOptions one_pass;
    one_pass.first_pass_pairs = 0;
    const Detector two(scenes.field), one(scenes.field, one_pass);
    int found_one = 0, found_two = 0;
    long grids_one = 0, grids_two = 0;
    for (auto category : {bench::Category::tiny, bench::Category::smeared}) {
        for (const auto& recipe : bench::category_recipes(scenes.scene, category, 20, 1)) {
            const bench::Frame frame = scenes.shoot(recipe, {640, 480});
            if (!frame.centre_on_screen) continue;
            const Detection a = one.detect(view_of(frame.grey)), b = two.detect(view_of(frame.grey));
            for (const Detection* d : {&a, &b}) {
                if (!d->found) continue;
                EXPECT_LT(scenes.error(frame, d->aim_field), 0.5) << to_string(category) << " frame " << recipe.index;
            }
            found_one += a.found;
            found_two += b.found;
            grids_one += a.grids_read;
            grids_two += b.grids_read;
        }
    }
    std::cout << "tiny and smeared: one pass " << found_one << " found, " << grids_one << " grids read; two passes "
              << found_two << " found, " << grids_two << " grids read\n";
    // Measured: 39 found either way; 751 grids read in one pass, 619 in two
    // (2955 and 1610 when this test was written; 1026 and 772 before the
    // part around the aim sent small modules to the lattice, which left
    // fewer grids read in vain for the second pass to save).
    EXPECT_GE(found_two, found_one);
    EXPECT_LT(grids_two, grids_one * 17 / 20);
}

// Modules of 3-4 pixels, which the first scan's edgels show
// (modules_look_small): the lattice runs before the first scan's grids,
// the content's, are each read in vain. A photo's search finds the same
// frames, reading far fewer grids. A tracker spreading its search over
// frames runs the first scan on each of them (spread_first()): with the
// cue it finds such a frame there, not a round of frames later when the
// lattice's share comes. The part around the aim, searched first, asks the
// cue of its own edgels: a frame the lattice finds reads no grid before it.
TEST(CategoryFloors, TinyModulesGoToTheLatticeBeforeTheContentsGrids) {
    const Scenes scenes(0.3);
    const Detector detector(scenes.field);
    FullSearch in_order = full_search();
    in_order[0].lattice_first_if_small = false;
    SearchPlan spread_without_cue = spread_first();
    spread_without_cue.lattice_first_if_small = false;
    int found = 0, found_in_order = 0, found_spread = 0, found_spread_without_cue = 0, frames = 0;
    int on_lattice = 0, on_lattice_at_once = 0;
    long grids = 0, grids_in_order = 0;
    for (const auto& recipe : bench::category_recipes(scenes.scene, bench::Category::tiny, 20, 1)) {
        const bench::Frame frame = scenes.shoot(recipe, {640, 480});
        if (!frame.centre_on_screen) continue;
        const GreyView view = view_of(frame.grey);
        const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
        const Detection a = detector.detect(view, centre, nullptr), b = detector.detect(view, centre, nullptr, in_order);
        const Detection c = detector.detect(view, centre, nullptr, spread_first());
        const Detection d = detector.detect(view, centre, nullptr, spread_without_cue);
        for (const Detection* e : {&a, &b, &c}) {
            if (!e->found) continue;
            EXPECT_LT(scenes.error(frame, e->aim_field), 0.5) << "frame " << recipe.index;
        }
        found += a.found;
        found_in_order += b.found;
        found_spread += c.found;
        found_spread_without_cue += d.found;
        on_lattice += a.found && a.from_lattice;
        on_lattice_at_once += a.found && a.from_lattice && a.grids_read == 1;
        grids += a.grids_read;
        grids_in_order += b.grids_read;
        ++frames;
    }
    std::cout << "tiny: lattice first " << found << " found, " << grids << " grids read; in order " << found_in_order
              << " found, " << grids_in_order << " grids read; a spread search's first scan " << found_spread << " of "
              << frames << " with the cue, " << found_spread_without_cue << " without; " << on_lattice
              << " found on the lattice, " << on_lattice_at_once << " of them reading no other grid\n";
    // Measured: 19 found either way; 526 grids read, 872 in order (a frame
    // found by neither reads some 370 either way; 1019 in order before the
    // lattice parts came first in kPartOrder, 2026-12-04; 629 and 822
    // before the part around the aim asked the cue); the spread's first
    // scan 17 of 20 with the cue, 6 without; 17 found on the lattice, all
    // 17 reading no other grid (14 and 1 before the part asked the cue).
    EXPECT_GE(found, found_in_order);
    EXPECT_LT(grids * 5, grids_in_order * 4);
    EXPECT_GE(found_spread, found_spread_without_cue + frames / 2);
    EXPECT_GE(on_lattice_at_once, frames / 2);
}

}  // namespace
