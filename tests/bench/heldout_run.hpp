// `umf_benchmark --set heldout`: the held-out set (heldout_scenario.hpp) for
// umf, umf video and ArUco on the same frames, written to heldout.json and
// heldout.md. Success: within half a module of the truth.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "shared/detect/tracker.hpp"
#include "tests/bench/heldout_scenario.hpp"

namespace umf::bench {

inline constexpr double kHeldoutRadiusModules = 0.5;
inline constexpr std::uint64_t kHeldoutScreenSeed = 101;  // the contents on the held-out screens

struct HeldoutOptions {
    int frames = 40;         // per category x opacity x resolution; 0: no sweep
    int pulse_frames = 90;   // per content in the pulsing video; 0: none
    std::string out = "docs/benchmarks";
    std::vector<HeldoutCategory> categories{kAllHeldoutCategories.begin(), kAllHeldoutCategories.end()};
    std::vector<cv::Size> resolutions{{640, 480}, {1280, 720}, {1920, 1080}};
    std::vector<double> opacities{0.15, 0.3, 0.5};
    bool aruco = true;
    bool video = true;
    std::uint64_t seed = 1;
    int threads = 1;
    std::string dump;
    std::string field = "b4-64x36.json";  // bench_field: a shipped name or a file's path
    std::string shown_field;               // on the screen, when another than `field`
    std::string command;
    TrackerOptions tracking;  // the trackers' (umf video)
    DetectorOptions detecting;  // the detector's (umf and umf video)
    double realtime = 0;      // umf video's device slowdown in real time (frame_clock.hpp); 0: offline
    double frame_share = 0;   // in real time, the share of a frame's time the spread search fits in (0: its budget)
    // Effects of the second camera model left out of every frame, to see
    // what each costs (diagnosis only; the held-out numbers of record have
    // all of them): pixel_structure, rolling_shutter, curved_blur,
    // exposure_hunt, processing, compression (or only its flat_macroblocks or
    // its video_jpeg).
    std::vector<std::string> without;
};

// Leaves the named effect out of a recipe; false for an unknown name.
bool leave_out(HeldoutRecipe& recipe, const std::string& effect);

int run_heldout(const HeldoutOptions& options);

}  // namespace umf::bench
