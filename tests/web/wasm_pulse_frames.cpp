// The native side of the WebAssembly pulse test (tests/web/wasm_pulse.mjs):
// a hand-held phone's frames of a web page whose field pulses between
// opacity 0.01 and 0.04 (sine, 1.5 s: the invisible preset), too faint for
// the tracker on any one frame, written as raw RGBA with each frame's time
// and the native PulseTracker's result on it, made as the page's detector
// makes it (a pulse set: detector_module.hpp's umf_set_pulse).
//
//   umf_wasm_pulse_frames OUT_DIR
//
// OUT_DIR/field.json      the field (umf-field/1)
// OUT_DIR/pulse_<i>.rgba  640 * 480 * 4 bytes, R G B A
// OUT_DIR/pulse.json      per frame: its time (ms), the state, whether the place was
//                         demodulated, the aim point, the truth, the native update's ms
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"
#include "tests/sim/sequence.hpp"

namespace {

using namespace umf;
using Json = nlohmann::ordered_json;

constexpr int kFrames = 36;           // 1.4 s at 25 fps
constexpr double kFrameMs = 40;       // 25 fps
constexpr double kStartMs = 5000.25;  // a clock that did not start with the video

Json point_json(bool valid, const Eigen::Vector2d& p) {
    return valid ? Json::array({p.x(), p.y()}) : Json(nullptr);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: umf_wasm_pulse_frames OUT_DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    const Field field = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    std::ofstream(dir / "field.json") << field_to_json(field);
    const Detector detector(field);
    const overlay::Preset invisible = *overlay::find_preset(overlay::built_in_presets(), "invisible");

    const sim::ScreenGeometry geometry;
    sim::CameraModel camera;
    camera.resolution = {640, 480};
    const sim::FieldPlacement placement{{0, 0}, 30};
    const cv::Mat screen = sim::make_screen(sim::ScreenKind::web_page, geometry.pixels, 5);
    sim::MotionRange range;
    range.distance_mm = 320;
    range.max_tilt_deg = 16;
    const auto poses = sim::pose_trajectory(sim::Motion::general, kFrames, geometry.pixels, 21, range);

    PulseSearchOptions pulse;
    pulse.shape = overlay::announced_pulse_shape(invisible.waveform, invisible.period_s, invisible.opacity_min,
                                                 invisible.opacity_max);
    PulseTracker tracker(detector, {}, pulse);
    Json frames = Json::array();
    std::vector<std::uint8_t> luma;
    int locked = 0;
    for (int i = 0; i < kFrames; ++i) {
        const double t_ms = kStartMs + i * kFrameMs;
        sim::Degradation deg;
        deg.noise_sigma = 2;
        deg.seed = 7000 + static_cast<std::uint64_t>(i);
        const double opacity = overlay::opacity_at(invisible, i * kFrameMs / 1000);
        const sim::Shot shot =
            sim::photograph(sim::mix_field(screen, field, placement, opacity), geometry, camera, poses[i], deg);
        cv::Mat rgba;
        cv::cvtColor(shot.bgr, rgba, cv::COLOR_BGR2RGBA);
        const std::string file = "pulse_" + std::to_string(i) + ".rgba";
        std::ofstream(dir / file, std::ios::binary)
            .write(reinterpret_cast<const char*>(rgba.data), static_cast<std::streamsize>(rgba.total() * 4));
        const GreyView view =
            to_luma({rgba.data, rgba.cols, rgba.rows, static_cast<std::ptrdiff_t>(rgba.step), PixelOrder::rgba}, luma);
        const PulseTrackResult r = tracker.update(view, {320, 240}, t_ms / 1000);
        const bool is_locked = r.track.state == TrackState::locked;
        locked += is_locked ? 1 : 0;
        const cv::Point2d truth = sim::image_to_field(shot, placement, {320, 240});
        frames.push_back({{"file", file},
                          {"time_ms", t_ms},
                          {"state", to_string(r.track.state)},
                          {"demodulated", r.demodulated},
                          {"point", point_json(is_locked, r.track.aim_field)},
                          {"truth", {truth.x, truth.y}},
                          {"ms", r.ms}});
        std::fprintf(stderr, "pulse frame %d: %s%s\n", i, to_string(r.track.state), r.demodulated ? " (demodulated)" : "");
    }
    const Json doc = {{"field", "field.json"},
                      {"width", 640},
                      {"height", 480},
                      {"pulse",
                       {{"waveform", overlay::to_string(invisible.waveform)},
                        {"period_s", invisible.period_s},
                        {"opacity_min", invisible.opacity_min},
                        {"opacity_max", invisible.opacity_max}}},
                      {"frames", frames}};
    std::ofstream(dir / "pulse.json") << doc.dump(1) << '\n';
    std::fprintf(stderr, "%d of %d frames locked\n", locked, kFrames);
    return 0;
}
