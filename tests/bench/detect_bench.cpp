// First detector measurements on simulated 640 x 480 photos: how often the
// field is found per screen kind and opacity over five poses, the worst aim
// error, and milliseconds per frame with the stage split. Not a test: it
// prints a Markdown table for docs/BENCHMARKS.md.
//   build/release/tests/umf_detect_bench [repeats]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "detect/detector.hpp"
#include "detect/photo.hpp"

using namespace umf;

int main(int argc, char** argv) {
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 100;
    Field f = test::shipped_field("b4-64x36.json");
    Detector detector(f);
    const char* names[] = {"document", "code_dark", "web_page", "photo", "blank"};
    const double poses[][4] = {{0, 0, 0, 300}, {20, 15, 70, 300}, {-30, 10, 140, 280}, {40, -25, 20, 250},
                               {10, 10, 100, 180}};
    std::printf("| screen | opacity | found (of 5 poses) | worst aim error (modules) | ms per frame (median pose) | pixels read |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (int k = 0; k < 5; ++k)
        for (double opacity : {0.3, 0.5}) {
            int found = 0;
            double worst = 0;
            std::vector<double> ms;
            double visited = 0;
            for (const auto& p : poses) {
                test::Photo photo =
                    test::photograph_field(f, opacity, p[0], p[1], p[2], p[3], static_cast<sim::ScreenKind>(k));
                Detection d;
                const auto t0 = std::chrono::steady_clock::now();
                for (int r = 0; r < repeats; ++r) d = detector.detect(photo.view());
                ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
                             repeats);
                visited += static_cast<double>(d.pixels_visited) / (640.0 * 480.0) / 5;
                if (!d.found) continue;
                ++found;
                const cv::Point2d truth = sim::image_to_field(photo.shot, photo.placement, {320, 240});
                worst = std::max(worst, std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y));
            }
            std::sort(ms.begin(), ms.end());
            std::printf("| %s | %.1f | %d | %.3f | %.2f | %.1f %% |\n", names[k], opacity, found, worst, ms[2],
                        100 * visited);
        }
    return 0;
}
