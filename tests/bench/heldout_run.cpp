#include "tests/bench/heldout_run.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "shared/field/field_io.hpp"
#include "tests/bench/methods.hpp"

namespace umf::bench {
namespace {

std::string now_text() {
    const std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M", std::localtime(&t));
    return buf;
}

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return in ? one + " " + five + " " + fifteen : "unknown";
}

std::string res_name(cv::Size s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

const char* const kSetup =
    "**Held-out set** (`umf_benchmark --set heldout`): scenes made apart from the tuning set, never looked at while "
    "changing the detector. Screens: a 13\" 2560 x 1600 laptop (286.5 mm, OLED PenTile), a 27\" 2560 x 1440 monitor "
    "(596.7 mm, RGB stripes) and a 15.6\" 1920 x 1080 laptop (344.2 mm, RGB stripes); the field across the screen's "
    "width (40, 40 and 30 px modules; on the 16:10 laptop centred, 80 px bands above and below). Contents: "
    "spreadsheet, dark-mode editor, video frame, landscape photo, board of tiles (`sim/heldout_content.hpp`). The "
    "second camera model (`sim/phone_camera.hpp`): a 70-80 degree phone camera at 30 fps, clips of 10 frames along "
    "curved hand paths, the screen turned at any roll in every category, rolling shutter (15-30 ms readout), metered "
    "exposure with auto-exposure hunting, shot and read noise, the phone's denoise (half the frames), sharpening "
    "halos and local tone mapping, video compression (flat-coded macroblocks, JPEG 35-60 with 4:2:0), defocus "
    "0.4-1.2 px, a curved smear of 1-3 px on 30 % of frames, the screen's pixel structure (4 x 4 samples per sensor pixel) on 20 %, a lamp's glare "
    "on 10 %. Pixel sizes are for 1280 px wide images and scale with the resolution. Categories (module px at "
    "1280 px width): general 10-30 px, tilt to 40 degrees; rotation 12-25 px, roll turning up to 120 degrees/s; "
    "perspective 12-25 px, tilt 35-60 degrees; near 35-80 px (pixel structure resolved on 60 %); far 6-9 px; "
    "motion 12-25 px with curved blur of 4-14 px; low_light: exposure 0.35-0.6, read noise 5-9, shot noise 8-14, "
    "strong denoise; occlusion: general plus a hand or mug over 15-35 % of the frame; moire: screen pixels of "
    "0.6-1.6 image px with the pixel structure sampled over each sensor pixel's area (2 x 2 or 3 x 3 point samples, no optical low-pass) before the optics. "
    "ArUco: the tuning set's board with cells of one module, blended in the same way.";

class HeldoutBench {
public:
    explicit HeldoutBench(const HeldoutOptions& opt)
        : opt_(opt), field_(bench_field(opt.field)),
          shown_(opt.shown_field.empty() ? field_ : bench_field(opt.shown_field)) {
        report_.title = "Detector benchmark, held-out set: umf against ArUco on a second camera model";
        report_.setup_md = kSetup;
        report_.json_name = "heldout.json";
        report_.success_radius_modules = kHeldoutRadiusModules;
        report_.pooled_over = "Pooled over all categories but occlusion and low_light, and all resolutions; module px = "
                              "image pixels per module (ArUco cell) at the image centre.";
        for (auto c : sim::kAllHeldoutContents) report_.screen_kinds.emplace_back(sim::to_string(c));
        report_.pulse_setup_md =
            "30 fps, the provider's default pulse (opacity 0.1 to 0.4 and back every 1.5 s, from a phase of each video's "
            "own), the second camera model with every everyday effect; one video per content, on the screen "
            "content % 3, along one continuous hand path (no cuts): modules of 10-30 px at 1280 px width, tilt to 40 "
            "degrees, the screen at any roll swinging by 10-30 degrees, the aim wandering over the middle of the "
            "screen";
        report_.command = opt.command;
        report_.started = now_text();
        settings();
        for (const auto& s : heldout_screens()) {
            placements_.push_back(heldout_placement(s, field_));
            const double module = placements_.back().module_px;
            methods_.push_back(std::make_unique<Methods>(field_, s.geometry.pixels, placements_.back(),
                                                         static_cast<int>(std::lround(module)), kHeldoutRadiusModules,
                                                         opt.tracking, opt.detecting));
        }
        const int n = static_cast<int>(heldout_screens().size() * sim::kAllHeldoutContents.size());
        screens_.resize(static_cast<std::size_t>(n));
        parallel_for(n, opt_.threads, [&](int k) {
            const auto& s = heldout_screens()[static_cast<std::size_t>(k) / sim::kAllHeldoutContents.size()];
            const auto c = sim::kAllHeldoutContents[static_cast<std::size_t>(k) % sim::kAllHeldoutContents.size()];
            screens_[static_cast<std::size_t>(k)] = sim::make_heldout_screen(c, s.geometry.pixels, kHeldoutScreenSeed);
        });
    }

    void sweep() {
        std::vector<std::vector<HeldoutRecipe>> recipes;
        for (HeldoutCategory c : opt_.categories) {
            recipes.push_back(heldout_recipes(c, opt_.frames, opt_.seed));
            for (auto& r : recipes.back())
                for (const auto& effect : opt_.without)
                    if (!leave_out(r, effect)) throw std::invalid_argument("--without: unknown effect '" + effect + "'");
        }
        const auto total = opt_.opacities.size() * opt_.resolutions.size() * opt_.categories.size();
        for (double opacity : opt_.opacities) {
            std::vector<cv::Mat> with_field(screens_.size()), with_board(screens_.size());
            parallel_for(static_cast<int>(screens_.size()), opt_.threads, [&](int k) {
                const auto i = static_cast<std::size_t>(k);
                const std::size_t s = i / sim::kAllHeldoutContents.size();
                with_field[i] = sim::mix_field(screens_[i], shown_, placements_[s], opacity);
                if (opt_.aruco) with_board[i] = methods_[s]->board().mix(screens_[i], opacity);
            });
            for (cv::Size res : opt_.resolutions)
                for (std::size_t ci = 0; ci < opt_.categories.size(); ++ci) {
                    configuration(opt_.categories[ci], recipes[ci], opacity, res, with_field, with_board);
                    const auto& cr = report_.configs.back();
                    std::cerr << "[" << report_.configs.size() << "/" << total << "] " << cr.category << " opacity "
                              << opacity << " " << cr.resolution << ": umf " << cr.methods.at("umf").success_pct << "%";
                    if (opt_.video) std::cerr << " | video " << cr.methods.at("umf_video").success_pct << "%";
                    if (opt_.aruco) std::cerr << " | ArUco " << cr.methods.at("aruco").success_pct << "%";
                    std::cerr << ", elapsed " << minutes() << " min\n";
                }
        }
    }

    // One video per content along one continuous path, the field pulsing as
    // the provider's default pulse: the opacity changes every frame, so the
    // screens are mixed per frame, on the frame-making threads.
    void pulsing(cv::Size res) {
        const cv::Size modules(field_.width, field_.height);
        PulseRun run(res_name(res), opt_.video, opt_.aruco);
        for (sim::HeldoutContent content : sim::kAllHeldoutContents) {
            const auto rs = heldout_pulsing_recipes(content, opt_.pulse_frames, opt_.seed);
            const auto s = static_cast<std::size_t>(rs.front().screen);
            const cv::Mat& screen = screens_[s * sim::kAllHeldoutContents.size() + static_cast<std::size_t>(content)];
            const Methods& m = *methods_[s];
            std::vector<Frame> field_frames(rs.size()), board_frames(rs.size());
            parallel_for(static_cast<int>(rs.size()), opt_.threads, [&](int i) {
                const auto at = static_cast<std::size_t>(i);
                const double op = heldout_pulsing_opacity(content, rs[at].index, opt_.seed);
                field_frames[at] = shoot_heldout(rs[at], sim::mix_field(screen, shown_, placements_[s], op), res,
                                                 placements_[s], modules);
                if (opt_.aruco) {
                    board_frames[at] = shoot_heldout(rs[at], m.board().mix(screen, op), res, placements_[s], modules);
                    board_frames[at].centre_on_screen = field_frames[at].centre_on_screen;
                }
            });
            std::vector<Outcome> u, v, a;
            for (std::size_t i = 0; i < rs.size(); ++i) {
                u.push_back(m.umf(field_frames[i]));
                if (opt_.aruco) a.push_back(m.aruco(board_frames[i]));
            }
            if (opt_.video) {
                FrameClock clock(opt_.realtime, kHeldoutFps);
                Tracker tracker = m.tracker(clock.machine_ms(opt_.frame_share));
                for (std::size_t i = 0; i < field_frames.size(); ++i)
                    v.push_back(m.video(tracker, field_frames[i], clock, static_cast<int>(i)));
            }
            run.add(sim::to_string(content), std::move(u), std::move(v), std::move(a), minutes());
        }
        run.summarise_into(report_);
    }

    void write() {
        report_.wall_s = minutes() * 60;
        report_.settings["load_average_at_end"] = load_average();
        const std::filesystem::path dir(opt_.out);
        std::filesystem::create_directories(dir);
        write_text(dir / "heldout.json", to_json(report_).dump(2) + "\n");
        write_text(dir / "heldout.md", to_markdown(report_));
        std::cerr << "wrote " << (dir / "heldout.md").string() << " and heldout.json; total wall time "
                  << report_.wall_s / 60 << " min\n";
    }

private:
    static void write_text(const std::filesystem::path& path, const std::string& text) {
        std::ofstream out(path);
        out << text;
        if (!out) throw std::runtime_error("cannot write " + path.string());
    }

    void settings() {
        nlohmann::json& s = report_.settings;
        s["set"] = "heldout";
        s["fps"] = kHeldoutFps;
        s["frames_per_configuration"] = opt_.frames;
        s["pulse_frames_per_content"] = opt_.pulse_frames;
        for (HeldoutCategory c : opt_.categories) s["categories"].push_back(to_string(c));
        for (cv::Size r : opt_.resolutions) s["resolutions"].push_back(res_name(r));
        s["opacities"] = opt_.opacities;
        s["aruco"] = opt_.aruco;
        s["umf_video"] = opt_.video;
        s["seed"] = opt_.seed;
        s["screen_seed"] = kHeldoutScreenSeed;
        s["frame_threads"] = opt_.threads;
        s["hardware_threads"] = std::thread::hardware_concurrency();
        s["load_average_at_start"] = load_average();
        s["field"] = opt_.field;
        s["shown_field"] = opt_.shown_field.empty() ? opt_.field : opt_.shown_field;
        for (const auto& sc : heldout_screens())
            s["screens"].push_back({{"name", sc.name}, {"pixels", res_name(sc.geometry.pixels)},
                                    {"width_mm", sc.geometry.width_mm}, {"layout", sim::to_string(sc.layout)}});
        s["success_radius_modules"] = kHeldoutRadiusModules;
        s["without"] = opt_.without;
        s["umf_video_tracker"] = {{"spread_search", opt_.tracking.spread_search},
                                  {"search_budget_ms", opt_.tracking.search_budget},
                                  {"realtime_slowdown", opt_.realtime},
                                  {"frame_share", opt_.frame_share},
                                  {"hold_first_scan", opt_.tracking.hold_first_scan},
                                  {"whole_frame_half_min_side", opt_.detecting.whole_frame_half_min_side},
                              {"first_scan_times", opt_.tracking.first_scan_times}};
    }

    void configuration(HeldoutCategory category, const std::vector<HeldoutRecipe>& rs, double opacity, cv::Size res,
                       const std::vector<cv::Mat>& with_field, const std::vector<cv::Mat>& with_board) {
        const cv::Size modules(field_.width, field_.height);
        std::vector<Frame> field_frames(rs.size()), board_frames(rs.size());
        parallel_for(static_cast<int>(rs.size()), opt_.threads, [&](int i) {
            const auto at = static_cast<std::size_t>(i);
            const auto s = static_cast<std::size_t>(rs[at].screen);
            const std::size_t k = s * sim::kAllHeldoutContents.size() + static_cast<std::size_t>(rs[at].content);
            field_frames[at] = shoot_heldout(rs[at], with_field[k], res, placements_[s], modules);
            if (opt_.aruco) {
                board_frames[at] = shoot_heldout(rs[at], with_board[k], res, placements_[s], modules);
                board_frames[at].centre_on_screen = field_frames[at].centre_on_screen;  // the same frames evaluated
            }
        });
        ConfigResult cr;
        cr.category = to_string(category);
        cr.opacity = opacity;
        cr.resolution = res_name(res);
        if (!opt_.dump.empty()) dump(cr, rs, field_frames, board_frames);

        ConfigOutcomes outcomes;
        for (std::size_t i = 0; i < rs.size(); ++i) {
            const Methods& m = *methods_[static_cast<std::size_t>(rs[i].screen)];
            outcomes.umf.push_back(m.umf(field_frames[i]));
            if (opt_.aruco) outcomes.aruco.push_back(m.aruco(board_frames[i]));
        }
        if (opt_.video) {
            // One tracker for the configuration; it only knows the field, so
            // the clips' cuts from one screen to another are cuts to it.
            FrameClock clock(opt_.realtime, kHeldoutFps);
            Tracker tracker = methods_.front()->tracker(clock.machine_ms(opt_.frame_share));
            for (std::size_t i = 0; i < rs.size(); ++i)
                outcomes.video.push_back(methods_[static_cast<std::size_t>(rs[i].screen)]->video(
                    tracker, field_frames[i], clock, static_cast<int>(i)));
        }
        std::vector<std::string> kinds;
        for (const auto& r : rs) kinds.emplace_back(sim::to_string(r.content));
        record_configuration(report_, cr, opacity, field_frames, kinds, outcomes,
                             category != HeldoutCategory::occlusion && category != HeldoutCategory::low_light);
        if (!opt_.dump.empty()) dump_outcomes(cr, outcomes.umf);
        report_.configs.push_back(std::move(cr));
    }

    std::string stem(const ConfigResult& cr, std::size_t i) const {
        return opt_.dump + "/heldout_" + cr.category + "_" + std::to_string(static_cast<int>(std::lround(cr.opacity * 100))) +
               "_" + cr.resolution + "_" + std::to_string(i);
    }

    void dump(const ConfigResult& cr, const std::vector<HeldoutRecipe>&, const std::vector<Frame>& field_frames,
              const std::vector<Frame>& board_frames) const {
        std::filesystem::create_directories(opt_.dump);
        for (std::size_t i = 0; i < field_frames.size(); ++i) {
            cv::imwrite(stem(cr, i) + "_umf.png", field_frames[i].grey);
            if (opt_.aruco) cv::imwrite(stem(cr, i) + "_aruco.png", board_frames[i].grey);
        }
    }

    // One line per frame: what umf said, for looking at the failures.
    void dump_outcomes(const ConfigResult& cr, const std::vector<Outcome>& out) const {
        std::ofstream log(opt_.dump + "/heldout_outcomes.tsv", std::ios::app);
        for (std::size_t i = 0; i < out.size(); ++i)
            log << stem(cr, i) << "\t" << (out[i].skipped ? "skipped" : out[i].success() ? "ok" : out[i].found ? "false" : "missed")
                << "\t" << out[i].error_modules << "\t" << out[i].failure << "\n";
    }

    double minutes() const { return ms_between(start_, BenchClock::now()) / 60000; }

    const HeldoutOptions& opt_;
    const BenchClock::time_point start_ = BenchClock::now();
    const Field field_;
    const Field shown_;  // on the screen; field_ unless shown_field
    std::vector<sim::FieldPlacement> placements_;
    std::vector<std::unique_ptr<Methods>> methods_;
    std::vector<cv::Mat> screens_;  // screen s, content c at s * contents + c
    Report report_;
};

}  // namespace

bool leave_out(HeldoutRecipe& r, const std::string& effect) {
    if (effect == "pixel_structure") r.shot.structure.reset();
    else if (effect == "rolling_shutter") r.shot.readout_s = 0;
    else if (effect == "curved_blur") r.shot.blur = {};
    else if (effect == "exposure_hunt") r.shot.hunt = 1;
    else if (effect == "processing") r.shot.processing = {};
    else if (effect == "compression") r.shot.compression = {};
    else if (effect == "flat_macroblocks") r.shot.compression.flat_threshold = 0;
    else if (effect == "video_jpeg") r.shot.compression.quality = 0;
    else return false;
    return true;
}

int run_heldout(const HeldoutOptions& opt) {
    cv::setNumThreads(1);
    HeldoutBench bench(opt);
    if (opt.frames > 0) bench.sweep();
    if (opt.pulse_frames > 0)
        for (cv::Size res : opt.resolutions) bench.pulsing(res);
    bench.write();
    return 0;
}

}  // namespace umf::bench
