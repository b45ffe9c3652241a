// The native side of the WebAssembly parity test (tests/web/wasm_parity.mjs):
// photographs a pulsing field with the camera simulator along a slow hand
// movement, writes each frame as raw RGBA (what the browser's VideoFrame and
// ImageData give the web client) and the native Tracker's result on it.
//
//   umf_wasm_parity_frames OUT_DIR [--bench RUNS]
//
// OUT_DIR/field.json      the field (umf-field/1), as the provider's welcome carries it
// OUT_DIR/<seq>_<i>.rgba  width*height*4 bytes, R G B A
// OUT_DIR/frames.json     per sequence and frame: the tracker's state, points, homography,
//                         windows, confidence, the grey image's FNV-1a hash
// With --bench, the native timing of the same calls as tests/web/wasm_bench.mjs:
// a search (reset, then one frame) and a locked frame (the sequence in order),
// RUNS times each, printed as JSON and written to OUT_DIR/native_bench.json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "shared/aiming/aim.hpp"
#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"
#include "tests/sim/sequence.hpp"

namespace {

using namespace umf;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

struct Sequence {
    std::string name;
    cv::Size size;
    int frames;
    int blank_frame;  // the field switched off here: the tracker must report "lost"
    std::uint64_t seed;
};

// 12 frames at 640 x 480 and 8 at 1280 x 720 (about half a second of a
// hand-held phone at 25 fps), each with one frame where the field is off.
const Sequence kSequences[] = {{"640x480", {640, 480}, 12, 7, 11}, {"1280x720", {1280, 720}, 8, 5, 12}};

struct Frame {
    cv::Mat rgba;
    cv::Point2d truth;
};

std::uint32_t fnv1a(const std::uint8_t* p, std::size_t n) {
    std::uint32_t h = 2166136261u;
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 16777619u;
    return h;
}

std::vector<Frame> photograph_sequence(const Field& field, const Sequence& s) {
    const sim::ScreenGeometry geometry;
    sim::CameraModel camera;
    camera.resolution = s.size;
    const sim::FieldPlacement placement{{0, 0}, 30};
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::document, geometry.pixels, 5);
    sim::MotionRange range;
    range.distance_mm = 320;
    range.max_tilt_deg = 30;
    const auto poses = sim::pose_trajectory(sim::Motion::general, s.frames, geometry.pixels, s.seed, range);
    std::vector<Frame> out;
    for (int i = 0; i < s.frames; ++i) {
        const double opacity = i == s.blank_frame ? 0 : sim::pulse_opacity(i / sim::kFps, 0.2, 0.45, 1.5);
        sim::Degradation deg;
        deg.noise_sigma = 2;
        deg.defocus_sigma_px = 0.7;
        deg.seed = s.seed * 1000 + i;
        const cv::Mat shown = opacity > 0 ? sim::mix_field(screen, field, placement, opacity) : screen;
        const sim::Shot shot = sim::photograph(shown, geometry, camera, poses[i], deg);
        Frame f;
        cv::cvtColor(shot.bgr, f.rgba, cv::COLOR_BGR2RGBA);
        f.truth = sim::image_to_field(shot, placement, {s.size.width / 2.0, s.size.height / 2.0});
        out.push_back(std::move(f));
    }
    return out;
}

GreyView grey_of(const cv::Mat& rgba, std::vector<std::uint8_t>& luma) {
    return to_luma({rgba.data, rgba.cols, rgba.rows, static_cast<std::ptrdiff_t>(rgba.step), PixelOrder::rgba}, luma);
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json point_json(bool valid, const Eigen::Vector2d& p) {
    return valid ? Json::array({p.x(), p.y()}) : Json(nullptr);
}

double median(std::vector<double> v) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

// One tracker call as the web module makes it: RGBA to grey, then update.
TrackResult track(Tracker& tracker, const cv::Mat& rgba, std::vector<std::uint8_t>& luma, double& ms) {
    const auto t0 = Clock::now();
    const GreyView view = grey_of(rgba, luma);
    const TrackResult r = tracker.update(view, Eigen::Vector2d(view.width / 2.0, view.height / 2.0));
    ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return r;
}

Json bench(const Detector& detector, const std::vector<Frame>& frames, const std::vector<TrackState>& states,
           int runs) {
    std::vector<std::uint8_t> luma;
    Tracker tracker(detector);
    std::vector<double> search, locked, miss, search_detect, locked_detect, miss_detect;
    double ms = 0;
    for (int run = 0; run < runs; ++run) {
        // Searching: every frame on its own after a reset (full detection).
        for (std::size_t i = 0; i < frames.size(); ++i) {
            tracker.reset();
            const TrackResult r = track(tracker, frames[i].rgba, luma, ms);
            (r.state == TrackState::locked ? search : miss).push_back(ms);
            (r.state == TrackState::locked ? search_detect : miss_detect).push_back(r.detection.times.total_ms);
        }
        // Locked: the sequence in order; frames locked after a locked frame.
        tracker.reset();
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const TrackResult r = track(tracker, frames[i].rgba, luma, ms);
            if (r.state == TrackState::locked && i > 0 && states[i - 1] == TrackState::locked) {
                locked.push_back(ms);
                locked_detect.push_back(r.detection.times.total_ms);
            }
        }
    }
    return {{"search_ms", number_or_null(median(search))},
            {"locked_ms", number_or_null(median(locked))},
            {"miss_ms", number_or_null(median(miss))},
            // The detector's own time (Detection::times.total_ms), without the grey conversion.
            {"search_detect_ms", number_or_null(median(search_detect))},
            {"locked_detect_ms", number_or_null(median(locked_detect))},
            {"miss_detect_ms", number_or_null(median(miss_detect))},
            {"samples", {{"search", search.size()}, {"locked", locked.size()}, {"miss", miss.size()}}}};
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 && !(argc == 4 && std::string(argv[2]) == "--bench")) {
        std::fprintf(stderr, "usage: umf_wasm_parity_frames OUT_DIR [--bench RUNS]\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    const int runs = argc == 4 ? std::atoi(argv[3]) : 0;
    std::filesystem::create_directories(dir);

    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    std::ofstream(dir / "field.json") << field_to_json(field);
    const Detector detector(field);

    Json doc = {{"field", "field.json"}, {"sequences", Json::array()}};
    Json bench_doc = {{"runs", runs}, {"sequences", Json::object()}};
    for (const Sequence& s : kSequences) {
        const std::vector<Frame> frames = photograph_sequence(field, s);
        Tracker tracker(detector);
        std::vector<std::uint8_t> luma;
        std::vector<TrackState> states;
        Json js = {{"name", s.name}, {"width", s.size.width}, {"height", s.size.height}, {"frames", Json::array()}};
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const std::string file = s.name + "_" + std::to_string(i) + ".rgba";
            const cv::Mat& rgba = frames[i].rgba;
            std::ofstream(dir / file, std::ios::binary)
                .write(reinterpret_cast<const char*>(rgba.data), static_cast<std::streamsize>(rgba.total() * 4));
            double ms = 0;
            const TrackResult r = track(tracker, rgba, luma, ms);
            states.push_back(r.state);
            const Detection& d = r.detection;
            const bool locked = r.state == TrackState::locked;
            Json H = Json::array();
            for (int k = 0; k < 9; ++k) H.push_back(d.found ? d.image_to_field(k / 3, k % 3) : (k % 4 == 0 ? 1.0 : 0.0));
            js["frames"].push_back({{"file", file},
                                    {"grey_fnv1a", fnv1a(luma.data(), luma.size())},
                                    {"state", to_string(r.state)},
                                    {"found", d.found},
                                    {"point", point_json(locked, r.aim_field)},
                                    {"raw_point", point_json(d.found, d.aim_field)},
                                    {"H", H},
                                    {"windows", d.windows},
                                    {"confidence", d.found ? umf::aiming::aim_confidence(d) : 0.0},
                                    {"used_prior", r.used_prior},
                                    {"frames_since_lock", r.frames_since_lock},
                                    {"edges_fitted", d.edges_fitted},
                                    {"failure", d.failure},
                                    {"truth", {frames[i].truth.x, frames[i].truth.y}},
                                    {"ms", ms}});
            std::fprintf(stderr, "%s frame %zu: %s windows %d%s\n", s.name.c_str(), i, to_string(r.state), d.windows,
                         d.found ? "" : (" (" + d.failure + ")").c_str());
        }
        doc["sequences"].push_back(js);
        if (runs > 0) bench_doc["sequences"][s.name] = bench(detector, frames, states, runs);
    }
    std::ofstream(dir / "frames.json") << doc.dump(1) << '\n';
    if (runs > 0) {
        std::ofstream(dir / "native_bench.json") << bench_doc.dump(1) << '\n';
        std::cout << bench_doc.dump(1) << '\n';
    }
    return 0;
}
