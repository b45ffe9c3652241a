// Diagnosis of wrong places on the tuning set: runs Detector::detect on
// umf_benchmark's frames of one category, opacity, resolution and seed (the
// same recipes and screens) and prints per frame what it found and by which
// path (size_scale, lattice, smoothed, windows, confidence, places checked,
// grids read), its error in modules (WRONG above 1), the error of the whole
// view's homography at the aim (view_error), and of a refit to the module
// edges within 4 modules of the aim on the frame itself. Tuning set only.
//   umf_false_hunt CATEGORY OPACITY WxH SEED FRAMES [first_frame] [dump_dir]
// UMF_HUNT_SCREEN=kind (e.g. code_dark): only the frames of that screen kind.
// dump_dir: the found frames' grey images as PNG.
#include <opencv2/imgcodecs.hpp>

#include <Eigen/Geometry>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "shared/detect/detector.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/refine.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"

using namespace umf;

int main(int argc, char** argv) {
    if (argc < 6) {
        std::cerr << "usage: umf_false_hunt CATEGORY OPACITY WxH SEED FRAMES [first_frame] [dump_dir]\n";
        return 2;
    }
    const auto category = bench::category_from_string(argv[1]);
    if (!category) return 2;
    const double opacity = std::stod(argv[2]);
    int w = 0, h = 0;
    std::sscanf(argv[3], "%dx%d", &w, &h);
    const auto seed = std::stoull(argv[4]);
    const int frames = std::stoi(argv[5]);
    const int first = argc > 6 ? std::stoi(argv[6]) : 0;
    const std::string dump = argc > 7 ? argv[7] : "";
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    const bench::Scene scene;
    const sim::FieldPlacement placement{{0, 0}, scene.module_px};
    const auto recipes = bench::category_recipes(scene, *category, frames, seed);
    std::vector<cv::Mat> screens(sim::kAllScreenKinds.size());
    const Detector detector(field);
    // UMF_HUNT_SCREEN=code_dark: only the frames of that screen kind.
    const char* only = std::getenv("UMF_HUNT_SCREEN");
    int found = 0, ok = 0, wrong = 0, evaluated = 0;
    for (const auto& r : recipes) {
        if (r.index < first) continue;
        if (only && std::string(only) != sim::to_string(r.screen)) continue;
        auto& screen = screens[static_cast<std::size_t>(r.screen)];
        if (screen.empty())
            screen = sim::mix_field(sim::make_screen(r.screen, scene.screen.pixels, 7), field, placement, opacity);
        const bench::Frame frame = bench::shoot(scene, r, screen, {w, h});
        if (!frame.centre_on_screen) {
            std::cout << "frame " << r.index << " skipped\n";
            continue;
        }
        ++evaluated;
        const GreyView view{frame.grey.data, frame.grey.cols, frame.grey.rows,
                            static_cast<std::ptrdiff_t>(frame.grey.step)};
        const Detection d = detector.detect(view);
        std::cout << "frame " << r.index << " screen " << sim::to_string(r.screen) << " module_px "
                  << frame.module_px_in_image << ": ";
        if (!d.found) {
            std::cout << "not found (" << d.failure << ") grids_read " << d.grids_read << " places_checked "
                      << d.places_checked << "\n";
            continue;
        }
        ++found;
        const double err =
            cv::norm(cv::Point2d(d.aim_field.x(), d.aim_field.y()) * scene.module_px - frame.centre_screen_px) /
            scene.module_px;
        ok += err <= 1;
        wrong += err > 1;
        std::cout << (err > 1 ? "WRONG " : "ok ") << "error " << err << " aim_field (" << d.aim_field.x() << ", "
                  << d.aim_field.y() << ") truth (" << frame.centre_screen_px.x / scene.module_px << ", "
                  << frame.centre_screen_px.y / scene.module_px << ") windows " << d.windows << " confidence "
                  << d.confidence << " size_scale " << d.size_scale << " lattice " << d.from_lattice << " smoothed "
                  << d.from_smoothed << " prior " << d.from_prior << " edges_fitted " << d.edges_fitted
                  << " places_checked " << d.places_checked << " grids_read " << d.grids_read;
        // Where the whole view's homography takes the aim, before the refit around it.
        const Eigen::Vector3d whole = d.image_to_field * Eigen::Vector3d(d.aim_image.x(), d.aim_image.y(), 1);
        const Eigen::Vector2d at = whole.hnormalized();
        std::cout << " view_error "
                  << cv::norm(cv::Point2d(at.x(), at.y()) * scene.module_px - frame.centre_screen_px) / scene.module_px
                  << " at_aim (" << at.x() << ", " << at.y() << ")";
        // The refit to the module edges within 4 modules of the aim, on the
        // frame itself, from the whole view's homography.
        RefineOptions around;
        around.max_radius_modules = 4;
        long visited = 0;
        const Refinement local = refine_homography(view, field, d.image_to_field.inverse(), at, around, visited);
        if (local.refined) {
            const auto p = apply_homography(local.field_to_image.inverse(), d.aim_image);
            if (p)
                std::cout << " local_refit_error "
                          << cv::norm(cv::Point2d(p->x(), p->y()) * scene.module_px - frame.centre_screen_px) /
                                 scene.module_px
                          << " moved " << (*p - at).norm() << " edges " << local.edges_fitted << " of "
                          << local.edges_found << " rms_px " << local.rms_px;
        } else {
            std::cout << " local_refit none (edges found " << local.edges_found << ")";
        }
        std::cout << "\n";
        if (!dump.empty())
            cv::imwrite(dump + "/" + argv[1] + "_" + argv[2] + "_" + argv[3] + "_s" + argv[4] + "_" +
                            std::to_string(r.index) + ".png",
                        frame.grey);
    }
    std::cout << "evaluated " << evaluated << " found " << found << " ok " << ok << " wrong " << wrong << "\n";
    return 0;
}
