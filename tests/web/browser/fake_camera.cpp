// The phone's camera for the browser tests (tests/web/browser/README.md): a
// Y4M video of the provider's screen, held by hand in front of one board
// tile, for Chromium's --use-file-for-fake-video-capture, and optionally one
// still photograph (PNG) for the page's photo mode.
//
//   umf_fake_camera --provider BIN --board BOARD.json --out VIDEO.y4m [options]
//   umf_fake_camera --provider BIN --demo-board --out VIDEO.y4m [options]
//   umf_fake_camera --provider BIN --content SCREEN.png --aim X,Y,W,H --out VIDEO.y4m [options]
//
// The screen is what the provider shows: `umf-provider compose` paints the
// board with the field mixed in at several phases of the pulse, and each frame
// takes the phase nearest its time. The camera aims at the centre of the
// chosen tile from a phone's distance, slightly tilted, and wanders around it
// by hand tremor. Tremor and pulse are both periodic over the video, so when
// Chromium loops the file the last frame runs smoothly into the first.
// Finally the native Tracker (PulseTracker for a faint pulse, as the page)
// is run over the frames (twice round the loop)
// as a check that the video can be grabbed at all: how many frames lock and
// whether the aim lands on the tile. A summary goes to stdout as JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "provider/board/board.hpp"
#include "shared/detect/detector.hpp"
#include "shared/detect/image.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/sim/camera.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/support/process.hpp"

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const char* const kUsage = R"(umf_fake_camera: a hand-held phone filming one board tile, as a Y4M video

usage:
  umf_fake_camera --provider BIN --board BOARD.json --out VIDEO.y4m [options]
  umf_fake_camera --provider BIN --demo-board --out VIDEO.y4m [options]
  umf_fake_camera --provider BIN --content SCREEN.png --aim X,Y,W,H --out VIDEO.y4m [options]

--provider BIN    umf-provider (its compose command paints the screen)
--board FILE      the board the provider serves (umf-board/1)
--demo-board      instead of --board: the built-in demo board (what
                  `umf-provider serve --headless` serves without --board),
                  written into the --work folder's demo-board/
--content FILE    instead of a board: a screenshot of a desktop, with the
                  field mixed in as the provider's overlay shows it
                  (`compose --content`); the screen is its size
--aim X,Y,W,H     the screen rectangle to aim at, in screen pixels (needed
                  with --content; with a board it replaces --tile's)
--out FILE        the video: YUV4MPEG2, 4:2:0 (C420jpeg), what Chromium's
                  --use-file-for-fake-video-capture plays in a loop
                  (BT.601 video range, as Chromium reads it)
--tile I          the board item to aim at, in board order (default 0)
--size WxH        video size (default 640x480; even numbers)
--frames N        number of frames (default 45: one 1.5 s pulse at 30 fps;
                  keep frames / fps a whole number of pulse periods so the
                  loop is seamless); 0: no video, only --still
--fps F           frame rate (default 30)
--phases P        screens composed over one pulse period and reused (default 9)
--preset NAME     a built-in preset of the provider (default kiosk, as for boards)
--screen WxH      the provider's screen (default 1920x1080)
--distance MM     camera distance from the screen (default 350)
--seed S          tremor and noise (default 1)
--still FILE.png  also one photograph of the tile (photo mode)
--still-size WxH  its size (default 1280x720)
--work DIR        composed screens and maps (default: VIDEO.y4m.screens)
--field-seed FILE the field-seed of the provider whose screen is filmed: its
                  own field is drawn (without: a seed made for this video)
--no-check        skip the native tracker's check

exit codes: 0 written (the check's result is in the summary, and a failed
check is reported on stderr); 2 usage; 3 compose or the board failed;
4 the check failed: fewer than half the frames locked on the tile (or
the --aim rectangle).
)";

// Below this opacity the check searches the frames together (the page's
// rule: web/site/faint_pulse.js, kFaintOpacity).
constexpr double kFaintOpacity = 0.1;

struct Options {
    std::string provider, board, content, out, still, work, field_seed, preset = "kiosk";
    std::optional<umf::provider::PixelRect> aim;
    int tile = 0, frames = 45, phases = 9;
    double fps = 30, distance_mm = 350;
    cv::Size size{640, 480}, still_size{1280, 720}, screen{1920, 1080};
    std::uint64_t seed = 1;
    bool check = true, demo_board = false;
};

struct Usage : std::runtime_error {
    using std::runtime_error::runtime_error;
};

cv::Size parse_size(const std::string& name, const std::string& text) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 16 || h < 16 || w > 8192 ||
        h > 8192)
        throw Usage("--" + name + " takes WxH, for example 640x480");
    return {w, h};
}

umf::provider::PixelRect parse_rect(const std::string& text) {
    umf::provider::PixelRect r;
    char c1 = 0, c2 = 0, c3 = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c%d%c%d", &r.x, &c1, &r.y, &c2, &r.width, &c3, &r.height) != 7 ||
        c1 != ',' || c2 != ',' || c3 != ',' || r.width < 1 || r.height < 1)
        throw Usage("--aim takes X,Y,W,H in screen pixels, for example 100,200,400,70");
    return r;
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::cout << kUsage;
            std::exit(0);
        }
        if (a == "--no-check") {
            o.check = false;
            continue;
        }
        if (a == "--demo-board") {
            o.demo_board = true;
            continue;
        }
        if (i + 1 >= argc) throw Usage(a + " needs a value");
        const std::string v = argv[++i];
        if (a == "--provider") o.provider = v;
        else if (a == "--board") o.board = v;
        else if (a == "--content") o.content = v;
        else if (a == "--aim") o.aim = parse_rect(v);
        else if (a == "--out") o.out = v;
        else if (a == "--still") o.still = v;
        else if (a == "--work") o.work = v;
        else if (a == "--field-seed") o.field_seed = v;
        else if (a == "--preset") o.preset = v;
        else if (a == "--tile") o.tile = std::stoi(v);
        else if (a == "--frames") o.frames = std::stoi(v);
        else if (a == "--phases") o.phases = std::stoi(v);
        else if (a == "--fps") o.fps = std::stod(v);
        else if (a == "--distance") o.distance_mm = std::stod(v);
        else if (a == "--seed") o.seed = std::stoull(v);
        else if (a == "--size") o.size = parse_size("size", v);
        else if (a == "--still-size") o.still_size = parse_size("still-size", v);
        else if (a == "--screen") o.screen = parse_size("screen", v);
        else throw Usage("unknown option " + a);
    }
    if (!o.board.empty() + o.demo_board + !o.content.empty() > 1)
        throw Usage("one of --board, --demo-board and --content");
    if (o.provider.empty() || (o.board.empty() && !o.demo_board && o.content.empty()))
        throw Usage("--provider and --board (or --demo-board, or --content) are needed");
    if (!o.content.empty() && !o.aim) throw Usage("--content needs --aim: where on the screen to point");
    if (o.frames > 0 && o.out.empty()) throw Usage("--out is needed (or --frames 0 and --still)");
    if (o.frames == 0 && o.still.empty()) throw Usage("--frames 0 makes only the still: --still is needed");
    if (o.size.width % 2 || o.size.height % 2) throw Usage("--size must be even in both directions (4:2:0)");
    if (o.frames < 0 || o.frames > 1000) throw Usage("--frames takes 0..1000");
    if (o.phases < 1 || o.phases > 100) throw Usage("--phases takes 1..100");
    if (!(o.fps > 0 && o.fps <= 120)) throw Usage("--fps takes 0..120");
    if (!(o.distance_mm >= 50 && o.distance_mm <= 5000)) throw Usage("--distance takes 50..5000 mm");
    if (o.work.empty()) o.work = (o.out.empty() ? o.still : o.out) + ".screens";
    return o;
}

std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

struct Phase {
    cv::Mat screen;
    umf::sim::FieldPlacement placement;
    std::string field_file;
};

// The screen the provider shows at pulse time t (umf-provider compose).
Phase compose(const Options& o, double t, int index) {
    const fs::path png = fs::path(o.work) / ("screen-" + std::to_string(index) + ".png");
    const fs::path map = fs::path(o.work) / ("map-" + std::to_string(index) + ".json");
    char time[32];
    std::snprintf(time, sizeof time, "%.4f", t);
    const std::string what = o.content.empty() ? " --board " + quoted(o.board) + " --screen " +
                                                     std::to_string(o.screen.width) + "x" +
                                                     std::to_string(o.screen.height)
                                               : " --content " + quoted(o.content);
    const std::string command = quoted(o.provider) + " compose" + what + " --preset " + quoted(o.preset) + " --time " + time + " --out " +
                                quoted(png.string()) + " --map " + quoted(map.string()) + " --config-dir " +
                                quoted((fs::path(o.work) / "config").string());
    const fs::path log = fs::path(o.work) / "compose.log";
    const auto r = umf::test::run_command(command + " 2>" + quoted(log.string()));
    if (r.exit_code != 0) {
        std::ifstream in(log);
        const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        throw std::runtime_error("compose failed (exit " + std::to_string(r.exit_code) + "): " + command + "\n" + err);
    }
    Phase p;
    p.screen = cv::imread(png.string(), cv::IMREAD_COLOR);
    if (p.screen.size() != o.screen) throw std::runtime_error("compose wrote no " + png.string());
    std::ifstream in(map);
    const Json m = Json::parse(in);
    p.placement = {{m.at("origin")[0].get<double>(), m.at("origin")[1].get<double>()}, m.at("module_px").get<double>()};
    p.field_file = m.at("field").get<std::string>();
    return p;
}

// A periodic wobble: a few sinusoids with whole numbers of cycles per loop.
struct Tremor {
    double amplitude[3], phase[3];
    int cycles[3];
    double at(double s) const {  // s in [0, 1): position in the loop
        double v = 0;
        for (int k = 0; k < 3; ++k) v += amplitude[k] * std::sin(2 * M_PI * cycles[k] * s + phase[k]);
        return v;
    }
};

Tremor make_tremor(std::mt19937_64& rng, double size) {
    std::uniform_real_distribution<double> ph(0, 2 * M_PI), am(0.5, 1.0);
    Tremor t{};
    const int cycles[3] = {1, 2, 3};
    for (int k = 0; k < 3; ++k) {
        t.cycles[k] = cycles[k];
        t.phase[k] = ph(rng);
        t.amplitude[k] = size * am(rng) / (k + 1);
    }
    return t;
}

// 8-bit BGR to I420 (BT.601, video range, as Chromium reads its fake capture).
void write_frame(std::ofstream& out, const cv::Mat& bgr) {
    cv::Mat yuv;
    cv::cvtColor(bgr, yuv, cv::COLOR_BGR2YUV_I420);
    out << "FRAME\n";
    out.write(reinterpret_cast<const char*>(yuv.data), static_cast<std::streamsize>(yuv.total()));
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        o = parse(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "umf_fake_camera: " << e.what() << "\n\n" << kUsage;
        return 2;
    }
    std::vector<Phase> phases;
    umf::provider::PixelRect tile;
    umf::provider::BoardItem item;
    double period = 1.5;
    try {
        if (o.demo_board) {
            umf::provider::write_demo_board(fs::path(o.work) / "demo-board");
            o.board = (fs::path(o.work) / "demo-board" / "board.json").string();
        }
        if (!o.content.empty()) {
            const cv::Mat content = cv::imread(o.content, cv::IMREAD_COLOR);
            if (content.empty()) throw std::runtime_error("--content " + o.content + " is not an image");
            o.screen = content.size();
        } else {
            const auto board = umf::provider::load_board(o.board);
            if (o.tile < 0 || o.tile >= static_cast<int>(board.items.size()))
                throw Usage("--tile " + std::to_string(o.tile) + ": the board has " +
                            std::to_string(board.items.size()) + " items");
            tile = umf::provider::layout_board(board, o.screen.width, o.screen.height)[o.tile];
            item = board.items[o.tile];
        }
        if (o.aim) tile = *o.aim;
        fs::create_directories(o.work);
        // The screen's own field is the one its provider's seed makes.
        if (!o.field_seed.empty()) {
            fs::create_directories(fs::path(o.work) / "config");
            fs::copy_file(o.field_seed, fs::path(o.work) / "config" / "field-seed",
                          fs::copy_options::overwrite_existing);
        }
        // The pulse period: the built-in preset's (a static preset: one phase).
        const auto presets = umf::overlay::built_in_presets();
        if (const auto* preset = umf::overlay::find_preset(presets, o.preset)) period = preset->period_s;
        if (period <= 0) {
            period = 1;
            o.phases = 1;
        }
        if (o.frames == 0) phases.push_back(compose(o, period / 4, 0));  // only the still's
        else
            for (int i = 0; i < o.phases; ++i) phases.push_back(compose(o, period * i / o.phases, i));
    } catch (const Usage& e) {
        std::cerr << "umf_fake_camera: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "umf_fake_camera: " << e.what() << "\n";
        return 3;
    }

    const umf::sim::ScreenGeometry geometry{o.screen, 527.0 * o.screen.width / 1920.0};
    const double mm_per_px = umf::sim::screen_mm_per_px(geometry);
    const cv::Point2d centre(tile.x + tile.width / 2.0, tile.y + tile.height / 2.0);
    std::mt19937_64 rng(o.seed);
    // Hand tremor: a few millimetres across, a degree or so of turn, ~1 cm of distance.
    const Tremor tx = make_tremor(rng, 4.0 / mm_per_px), ty = make_tremor(rng, 3.0 / mm_per_px);
    const Tremor roll = make_tremor(rng, 1.5), yaw = make_tremor(rng, 1.0), pitch = make_tremor(rng, 1.0),
                 dist = make_tremor(rng, 6.0);
    std::uniform_real_distribution<double> lean(-12, 12);
    const double base_yaw = lean(rng), base_pitch = 6 + lean(rng) / 3, base_roll = lean(rng) / 2;

    auto pose_at = [&](double s) {
        umf::sim::CameraPose pose;
        pose.distance_mm = o.distance_mm + dist.at(s);
        pose.yaw_deg = base_yaw + yaw.at(s);
        pose.pitch_deg = base_pitch + pitch.at(s);
        pose.roll_deg = base_roll + roll.at(s);
        pose.aim_screen_px = centre + cv::Point2d(tx.at(s), ty.at(s));
        return pose;
    };
    auto degradation_for = [&](int i) {
        umf::sim::Degradation d;
        d.noise_sigma = 2;
        d.defocus_sigma_px = 0.6;
        d.seed = o.seed * 100003 + static_cast<std::uint64_t>(i);
        return d;
    };

    const umf::sim::CameraModel camera{o.size, 65};
    std::vector<cv::Mat> frames;
    std::vector<int> frame_phase;
    if (o.frames > 0) {
        std::ofstream video(o.out, std::ios::binary | std::ios::trunc);
        if (!video) {
            std::cerr << "umf_fake_camera: cannot write " << o.out << "\n";
            return 3;
        }
        char fps[32];
        if (std::abs(o.fps - std::round(o.fps)) < 1e-9) std::snprintf(fps, sizeof fps, "%d:1", static_cast<int>(o.fps));
        else std::snprintf(fps, sizeof fps, "%d:1000", static_cast<int>(std::round(o.fps * 1000)));
        video << "YUV4MPEG2 W" << o.size.width << " H" << o.size.height << " F" << fps << " Ip A1:1 C420jpeg\n";

        for (int i = 0; i < o.frames; ++i) {
            const double t = i / o.fps;
            const int p = static_cast<int>(std::lround(std::fmod(t, period) / period * phases.size())) %
                          static_cast<int>(phases.size());
            const auto shot = umf::sim::photograph(phases[p].screen, geometry, camera,
                                                   pose_at(static_cast<double>(i) / o.frames), degradation_for(i));
            write_frame(video, shot.bgr);
            if (o.check) frames.push_back(shot.bgr);
            frame_phase.push_back(p);
        }
        video.close();
        if (!video) {
            std::cerr << "umf_fake_camera: writing " << o.out << " failed\n";
            return 3;
        }
    }

    Json summary = {{"video", o.frames > 0 ? Json(o.out) : Json(nullptr)},
                    {"size", {o.size.width, o.size.height}},
                    {"frames", o.frames},
                    {"fps", o.fps},
                    {"bytes", o.frames > 0 ? fs::file_size(o.out) : 0},
                    {"board", o.board.empty() ? Json(nullptr) : Json(o.board)},
                    {"content", o.content.empty() ? Json(nullptr) : Json(o.content)},
                    {"preset", o.preset},
                    {"tile", o.tile},
                    {"title", item.title},
                    {"kind", !o.content.empty() ? "window" : item.file ? "file" : "url"},
                    {"tile_rect", {tile.x, tile.y, tile.width, tile.height}},
                    {"aim_screen_px", {centre.x, centre.y}},
                    {"pose", {{"distance_mm", o.distance_mm}, {"yaw_deg", base_yaw}, {"pitch_deg", base_pitch},
                              {"roll_deg", base_roll}}}};
    if (item.file) summary["file"] = item.file->string();
    if (item.url) summary["url"] = *item.url;

    if (!o.still.empty()) {
        // Photo mode: a quarter period into the pulse (opacity half way
        // between the preset's minimum and maximum), held by hand.
        const std::size_t p = o.frames == 0 ? 0 : phases.size() / 4;
        auto d = degradation_for(o.frames);
        d.jpeg_quality = 90;
        const auto shot = umf::sim::photograph(phases[p].screen, geometry, {o.still_size, 65}, pose_at(0.37), d);
        if (!cv::imwrite(o.still, shot.bgr)) {
            std::cerr << "umf_fake_camera: cannot write " << o.still << "\n";
            return 3;
        }
        summary["still"] = o.still;
    }

    int exit_code = 0;
    if (o.check && o.frames > 0) {
        // The native tracker, as the page's worker runs it: RGBA from the
        // decoded video (here: the I420 round trip), twice round the loop.
        const umf::Field field = umf::load_field(phases[0].field_file);
        const umf::Detector detector(field);
        umf::Tracker tracker(detector);
        // A pulse too faint for one frame is searched over the frames, as
        // the page searches it (web/site/faint_pulse.js).
        std::optional<umf::PulseTracker> pulse_tracker;
        const auto presets = umf::overlay::built_in_presets();
        if (const auto* preset = umf::overlay::find_preset(presets, o.preset);
            preset && preset->period_s > 0 && preset->opacity_max < kFaintOpacity) {
            umf::PulseSearchOptions pulse;
            pulse.shape = umf::overlay::announced_pulse_shape(preset->waveform, preset->period_s, preset->opacity_min,
                                                              preset->opacity_max);
            pulse_tracker.emplace(detector, umf::TrackerOptions{}, pulse);
        }
        int locked = 0, on_tile = 0, first_lock = -1;
        std::vector<std::uint8_t> luma;
        for (int round = 0; round < 2; ++round) {
            for (int i = 0; i < o.frames; ++i) {
                cv::Mat yuv, rgba;
                cv::cvtColor(frames[i], yuv, cv::COLOR_BGR2YUV_I420);
                cv::cvtColor(yuv, rgba, cv::COLOR_YUV2RGBA_I420);
                const umf::GreyView view = umf::to_luma(
                    {rgba.data, rgba.cols, rgba.rows, static_cast<std::ptrdiff_t>(rgba.step), umf::PixelOrder::rgba},
                    luma);
                const Eigen::Vector2d aim(view.width / 2.0, view.height / 2.0);
                const double t = (round * o.frames + i) / o.fps;
                const umf::TrackResult r = pulse_tracker ? pulse_tracker->update(view, aim, t).track
                                                         : tracker.update(view, aim);
                if (r.state != umf::TrackState::locked) continue;
                if (first_lock < 0) first_lock = round * o.frames + i;
                if (round == 0) continue;
                ++locked;
                const auto& pl = phases[frame_phase[i]].placement;
                const cv::Point2d s = umf::sim::field_to_screen(pl, {r.aim_field.x(), r.aim_field.y()});
                on_tile += tile.contains(s.x, s.y);
            }
        }
        summary["check"] = {{"locked", locked}, {"on_tile", on_tile}, {"of", o.frames}, {"first_lock_frame", first_lock}};
        if (on_tile * 2 < o.frames) {
            std::cerr << "umf_fake_camera: the native tracker locked on the tile in only " << on_tile << " of "
                      << o.frames << " frames\n";
            exit_code = 4;
        }
    }
    std::cout << summary.dump() << std::endl;
    return exit_code;
}
