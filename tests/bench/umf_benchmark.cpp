// The detector benchmark of record: the umf detector against OpenCV's ArUco
// markers on simulated phone frames of a screen, per test category, field
// opacity and camera resolution, plus a pulsing-opacity video. Three
// methods: "umf" (Detector::detect on every frame on its own), "umf_video"
// (a Tracker fed a configuration's frames in their order, as a phone feeds
// its camera frames) and "aruco". Writes detector.json, detector.md and two
// PNG charts (see --help).
//
// Frames are made on all cores; the detectors are then timed one after the
// other on one thread each, so that frame making never competes with a
// timed call.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/tracker.hpp"
#include "shared/field/field_io.hpp"
#include "tests/bench/aruco_baseline.hpp"
#include "tests/bench/heldout_run.hpp"
#include "tests/bench/methods.hpp"
#include "tests/bench/metrics.hpp"
#include "tests/bench/plot.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/screen_content.hpp"

namespace {

using namespace umf;
using namespace umf::bench;
using Clock = BenchClock;

constexpr std::uint64_t kScreenSeed = 7;

const char* const kUsage = R"(umf_benchmark: the umf detector (single frame and video) against ArUco on simulated phone frames.

Usage: umf_benchmark [options]
  --frames N             frames per category x opacity x resolution (default 40; 0 = only the pulsing video)
  --set tuning|heldout   tuning (default): the scenes the detector is tuned on, written to
                         detector.{json,md} and two PNGs; heldout: the held-out scenes (other screens,
                         contents, camera model and seeds; success within half a module), written to
                         heldout.{json,md}
  --quick                10 frames, 640x480 only, a short pulsing run (explicit options win)
  --out DIR              where the reports go (default docs/benchmarks)
  --categories a,b       tuning: near_far, horizontal, rotation, perspective, general, occlusion, low_light,
                         smeared, distant, compressed, tiny, pixel_grid, ruled, sensor;
                         heldout: general, rotation, perspective, near, far, motion, low_light, occlusion,
                         moire (default all)
  --resolutions WxH,...  camera resolutions (default 640x480,1280x720,1920x1080)
  --opacities a,b        field and board opacities (default 0.1,0.15,0.2,0.3,0.5; heldout 0.15,0.3,0.5)
  --success-radius R     tuning only: success within R modules (default 1; the held-out set's is 0.5),
                         to compare the tuning set with the held-out set on the held-out criterion
  --without a,b          heldout only, for diagnosis: leave effects of the second camera model out
                         (pixel_structure, rolling_shutter, curved_blur, exposure_hunt, processing, compression,
                         or of compression only flat_macroblocks or video_jpeg)
  --no-aruco             leave ArUco out
  --no-video             leave "umf video" (the tracker over consecutive frames) out
  --pulse-frames N       frames per screen content in the pulsing video (default 150, heldout 90, quick 50;
                         0 = skip)
  --seed N               scenario seed (default 1)
  --threads N            threads making frames (default: all cores)
  --spread-search BUDGET|auto
                         "umf video": a tracker without a lock spreads its search over frames, each the first
                         scan's first piece and pieces within BUDGET (TrackerOptions::search_budget; default: off);
                         auto, with --realtime: the first scan and the round's steps from where the last frame
                         stopped, held to half the device's time between two frames (TrackerOptions::frame_ms)
  --hold-first-scan      with --spread-search auto: the first scan held to a time too, all but its search
                         around the aim (TrackerOptions::hold_first_scan)
  --first-scan-times X   --hold-first-scan, its time X times the spread search's (TrackerOptions::
                         first_scan_times; default 2, the device's whole time between two frames)
  --whole-frame-half-min-side N  a tracker's first scan of the whole frame at half size where that keeps
                         N rows (DetectorOptions::whole_frame_half_min_side; default 360; 0: never)
  --realtime SLOWDOWN    "umf video" in real time on a device SLOWDOWN times slower than this machine: the
                         frames arrive at the video's rate (25 a second; held-out 30) and one that arrives
                         while the tracker is still on an earlier frame is dropped, counted as not found
                         (default 0: every frame looked at, however long the tracker takes)
  --dump DIR             also save every frame as PNG there (for looking at them; use with few frames)
  --field NAME|FILE      the 64 x 36 field the detector looks for: a shipped one of shared/data/fields
                         (default b4-64x36.json) or a field file's path (one with a '/')
  --shown-field NAME|FILE
                         the field on the screen when it is another than --field: every frame found is
                         then a point taken from a screen the requester is not paired with (default: --field)
  --help                 this text

Progress goes to stderr. The detectors are timed on one thread each.
)";

struct Options {
    bool heldout = false;
    std::vector<std::string> category_names;  // as given; resolved once the set is known
    bool opacities_given = false;
    std::vector<std::string> without;
    double radius = kSuccessRadiusModules;  // tuning set's success radius in modules
    bool radius_given = false;
    int frames = 40;
    std::string out = "docs/benchmarks";
    std::vector<Category> categories{kAllCategories.begin(), kAllCategories.end()};
    std::vector<cv::Size> resolutions{{640, 480}, {1280, 720}, {1920, 1080}};
    std::vector<double> opacities{0.1, 0.15, 0.2, 0.3, 0.5};
    bool aruco = true;
    bool video = true;
    int pulse_frames = 150;
    std::uint64_t seed = 1;
    int threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    std::string dump;
    std::string field = "b4-64x36.json";
    std::string shown_field;  // empty: field
    double realtime = 0;      // umf video's device slowdown in real time (frame_clock.hpp); 0: offline
    double frame_share = 0;   // in real time, the share of a frame's time the spread search fits in (0: its budget)
    TrackerOptions tracking;
    DetectorOptions detecting;
};

std::vector<std::string> split(const std::string& list) {
    std::vector<std::string> out;
    std::stringstream in(list);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

std::string resolution_name(cv::Size s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

int positive_int(const std::string& text, const std::string& what, int min = 1) {
    std::size_t used = 0;
    int v = 0;
    try {
        v = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || v < min) throw std::invalid_argument(what + ": not a number >= " + std::to_string(min));
    return v;
}

double non_negative_number(const std::string& text, const std::string& what) {
    std::size_t used = 0;
    double v = -1;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || !(v >= 0)) throw std::invalid_argument(what + ": not a number >= 0");
    return v;
}

Options parse(int argc, char** argv) {
    Options o;
    bool quick = false, frames_given = false, res_given = false, pulse_given = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else if (a == "--frames") {
            o.frames = positive_int(value(), a, 0);
            frames_given = true;
        } else if (a == "--quick") {
            quick = true;
        } else if (a == "--out") {
            o.out = value();
        } else if (a == "--set") {
            const std::string set = value();
            if (set != "tuning" && set != "heldout") throw std::invalid_argument("--set takes tuning or heldout");
            o.heldout = set == "heldout";
        } else if (a == "--categories") {
            o.category_names = split(value());
            if (o.category_names.empty()) throw std::invalid_argument("nothing to run: empty category list");
        } else if (a == "--resolutions") {
            o.resolutions = parse_resolutions(value());
            res_given = true;
        } else if (a == "--opacities") {
            o.opacities_given = true;
            o.opacities.clear();
            for (const auto& v : split(value())) {
                const double op = std::stod(v);
                if (!(op > 0 && op <= 1)) throw std::invalid_argument("opacity " + v + " is not in (0, 1]");
                o.opacities.push_back(op);
            }
        } else if (a == "--success-radius") {
            o.radius = std::stod(value());
            o.radius_given = true;
            if (!(o.radius > 0)) throw std::invalid_argument("--success-radius must be > 0");
        } else if (a == "--without") {
            o.without = split(value());
        } else if (a == "--no-aruco") {
            o.aruco = false;
        } else if (a == "--no-video") {
            o.video = false;
        } else if (a == "--pulse-frames") {
            o.pulse_frames = positive_int(value(), a, 0);
            pulse_given = true;
        } else if (a == "--seed") {
            o.seed = static_cast<std::uint64_t>(positive_int(value(), a, 0));
        } else if (a == "--threads") {
            o.threads = positive_int(value(), a);
        } else if (a == "--spread-search") {
            const std::string budget = value();
            if (budget == "auto")
                o.frame_share = kSpreadFrameShare;  // as the page gives it
            else
                o.tracking.search_budget = non_negative_number(budget, a);
            o.tracking.spread_search = true;
        } else if (a == "--hold-first-scan") {
            o.tracking.hold_first_scan = true;
        } else if (a == "--first-scan-times") {
            o.tracking.first_scan_times = non_negative_number(value(), a);
            if (!(o.tracking.first_scan_times > 0)) throw std::invalid_argument("--first-scan-times must be > 0");
            o.tracking.hold_first_scan = true;
        } else if (a == "--whole-frame-half-min-side") {
            o.detecting.whole_frame_half_min_side = positive_int(value(), a, 0);
        } else if (a == "--realtime") {
            o.realtime = non_negative_number(value(), a);
        } else if (a == "--field") {
            o.field = value();
        } else if (a == "--shown-field") {
            o.shown_field = value();
        } else if (a == "--dump") {
            o.dump = value();
        } else {
            throw std::invalid_argument("unknown option '" + a + "' (see --help)");
        }
    }
    if (!o.heldout && !o.without.empty()) throw std::invalid_argument("--without is for --set heldout only");
    if (o.heldout && o.radius_given) throw std::invalid_argument("--success-radius is for the tuning set (the held-out set's is half a module)");
    if (!o.heldout && !o.category_names.empty()) {
        o.categories.clear();
        for (const auto& name : o.category_names) {
            const auto c = category_from_string(name);
            if (!c) throw std::invalid_argument("unknown category '" + name + "'");
            o.categories.push_back(*c);
        }
    }
    if (o.tracking.hold_first_scan && !(o.frame_share > 0))
        throw std::invalid_argument("--hold-first-scan holds the search to the frames' time: give --spread-search auto");
    if (o.frame_share > 0 && !(o.realtime > 0))
        throw std::invalid_argument("--spread-search auto measures against the frames' time: give --realtime too");
    if (o.heldout && !pulse_given) o.pulse_frames = 90;
    if (quick) {
        if (!frames_given) o.frames = 10;
        if (!res_given) o.resolutions = {{640, 480}};
        if (!pulse_given) o.pulse_frames = 50;
    }
    if (o.frames == 0 && o.pulse_frames == 0) throw std::invalid_argument("nothing to run: no frames and no pulsing video");
    if (o.categories.empty() || o.resolutions.empty() || o.opacities.empty())
        throw std::invalid_argument("nothing to run: empty category, resolution or opacity list");
    return o;
}


// Other processes on the machine slow the timed calls down; the load
// average before and after the run says how much there was.
std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return in ? one + " " + five + " " + fifteen : "unknown";
}

std::string now_text() {
    const std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M", std::localtime(&t));
    return buf;
}

std::string short_result(const Summary& s) {
    std::ostringstream o;
    o.precision(3);
    o << s.success_pct << "% ok, " << s.false_pct << "% false, " << s.ms_median << " ms";
    return o.str();
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
    if (!cv::imwrite(path.string(), image)) throw std::runtime_error("cannot write " + path.string());
}

void write_plots(const Report& report, const std::filesystem::path& dir) {
    std::vector<std::string> methods;
    for (const auto& m : kMethods)
        if (report.all_ms.count(m.key)) methods.emplace_back(m.key);
    std::vector<std::string> resolutions, categories;
    std::vector<double> opacities;
    for (const auto& c : report.configs) {
        if (std::find(resolutions.begin(), resolutions.end(), c.resolution) == resolutions.end())
            resolutions.push_back(c.resolution);
        if (std::find(categories.begin(), categories.end(), c.category) == categories.end())
            categories.push_back(c.category);
        if (std::find(opacities.begin(), opacities.end(), c.opacity) == opacities.end()) opacities.push_back(c.opacity);
    }
    std::sort(opacities.begin(), opacities.end());
    const std::string sweep =
        std::find(categories.begin(), categories.end(), "general") != categories.end() ? "general" : categories.front();

    // One colour per resolution; umf solid with circles, umf video dotted
    // with triangles, ArUco dashed with squares.
    std::vector<plot::Series> lines;
    for (std::size_t r = 0; r < resolutions.size(); ++r)
        for (const auto& m : methods) {
            plot::Series s;
            s.label = method_label(m) + " " + resolutions[r];
            s.colour = plot::colour(static_cast<int>(r));
            s.dashed = s.square_markers = m == "aruco";
            s.dotted = s.triangle_markers = m == "umf_video";
            for (double op : opacities)
                for (const auto& c : report.configs)
                    if (c.category == sweep && c.resolution == resolutions[r] && c.opacity == op &&
                        c.methods.count(m)) {
                        s.x.push_back(op);
                        s.y.push_back(c.methods.at(m).success_pct);
                    }
            lines.push_back(s);
        }
    std::ostringstream radius;
    radius << report.success_radius_modules;
    const std::string within = "success % (within " + radius.str() + " module)";
    plot::Axes axes{"Success against opacity (" + sweep + " category)", "opacity", within,
                    std::make_pair(0.0, 100.0)};
    write_png(dir / "success_vs_opacity.png", plot::line_chart(axes, lines));

    plot::Bars bars;
    bars.groups = resolutions;
    for (std::size_t m = 0; m < methods.size(); ++m) {
        bars.series.push_back(method_label(methods[m]));
        bars.colours.push_back(plot::colour(methods[m] == "umf" ? 0 : methods[m] == "umf_video" ? 2 : 3));
        std::vector<double> row;
        for (const auto& res : resolutions) {
            const auto& by_res = report.all_ms.at(methods[m]);
            auto it = by_res.find(res);
            row.push_back(it == by_res.end() ? kNaN : percentile(it->second, 50));
        }
        bars.values.push_back(row);
    }
    write_png(dir / "ms_per_frame.png",
              plot::bar_chart({"Median ms per frame (one thread, all categories and opacities)", "camera resolution",
                               "ms per frame", std::nullopt},
                              bars));
}

nlohmann::json settings_json(const Options& opt, const Scene& scene, const Methods& methods) {
    nlohmann::json s;
    s["frames_per_configuration"] = opt.frames;
    for (Category c : opt.categories) s["categories"].push_back(to_string(c));
    for (cv::Size r : opt.resolutions) s["resolutions"].push_back(resolution_name(r));
    s["opacities"] = opt.opacities;
    s["aruco"] = opt.aruco;
    s["umf_video"] = opt.video;
    s["pulse_frames_per_screen"] = opt.pulse_frames;
    s["seed"] = opt.seed;
    s["frame_threads"] = opt.threads;
    s["hardware_threads"] = std::thread::hardware_concurrency();
    s["load_average_at_start"] = load_average();
    s["field"] = opt.field;
    s["shown_field"] = opt.shown_field.empty() ? opt.field : opt.shown_field;
    s["screen"] = {{"pixels", "1920x1080"}, {"width_mm", scene.screen.width_mm}, {"module_px", scene.module_px}};
    s["camera_hfov_deg"] = scene.hfov_deg;
    s["distance_mm"] = {{"rest", scene.range.distance_mm}, {"near", scene.range.near_mm}, {"far", scene.range.far_mm}};
    s["aruco_board"] = {{"dictionary", "DICT_4X4_250"}, {"markers", methods.board().marker_count()},
                        {"marker_px", 180}, {"gap_px", 60}};
    s["success_radius_modules"] = opt.radius;
    s["umf_video_tracker"] = {{"spread_search", opt.tracking.spread_search},
                              {"search_budget_ms", opt.tracking.search_budget},
                              {"realtime_slowdown", opt.realtime},
                              {"frame_share", opt.frame_share},
                              {"hold_first_scan", opt.tracking.hold_first_scan},
                              {"whole_frame_half_min_side", opt.detecting.whole_frame_half_min_side},
                              {"first_scan_times", opt.tracking.first_scan_times}};
    return s;
}

// One benchmark run: the fixed setup, and the report it fills.
class Bench {
public:
    Bench(const Options& opt, const std::string& command)
        : opt_(opt), field_(bench_field(opt.field)),
          shown_(opt.shown_field.empty() ? field_ : bench_field(opt.shown_field)),
          methods_(field_, scene_.screen.pixels, sim::FieldPlacement{{0, 0}, scene_.module_px}, 30, opt.radius,
                   opt.tracking, opt.detecting) {
        report_.success_radius_modules = opt.radius;
        report_.command = command;
        report_.started = now_text();
        report_.settings = settings_json(opt_, scene_, methods_);
        // Screens once per kind (the photo kind takes a while); both
        // methods' screens are mixed from the same content.
        screens_.resize(sim::kAllScreenKinds.size());
        parallel_for(static_cast<int>(screens_.size()), opt_.threads, [&](int k) {
            screens_[static_cast<std::size_t>(k)] =
                sim::make_screen(sim::kAllScreenKinds[static_cast<std::size_t>(k)], scene_.screen.pixels, kScreenSeed);
        });
    }

    void sweep() {
        std::vector<std::vector<FrameRecipe>> recipes;
        for (Category c : opt_.categories) recipes.push_back(category_recipes(scene_, c, opt_.frames, opt_.seed));
        const auto total = opt_.opacities.size() * opt_.resolutions.size() * opt_.categories.size();
        for (double opacity : opt_.opacities) {
            std::vector<cv::Mat> with_field(screens_.size()), with_board(screens_.size());
            parallel_for(static_cast<int>(screens_.size()), opt_.threads, [&](int k) {
                const auto i = static_cast<std::size_t>(k);
                with_field[i] = sim::mix_field(screens_[i], shown_, placement_, opacity);
                if (opt_.aruco) with_board[i] = methods_.board().mix(screens_[i], opacity);
            });
            for (cv::Size res : opt_.resolutions)
                for (std::size_t ci = 0; ci < opt_.categories.size(); ++ci) {
                    configuration(opt_.categories[ci], recipes[ci], opacity, res, with_field, with_board);
                    std::cerr << "[" << report_.configs.size() << "/" << total << "] " << progress(report_.configs.back())
                              << ", elapsed " << minutes() << " min\n";
                }
        }
    }

    // The pulsing video: the opacity changes every frame, so both screens
    // are mixed per frame, on the frame-making threads.
    void pulsing(cv::Size res) {
        PulseRun run(resolution_name(res), opt_.video, opt_.aruco);
        for (std::size_t k = 0; k < sim::kEverydayScreenKinds.size(); ++k) {
            const auto rs = pulsing_recipes(scene_, sim::kEverydayScreenKinds[k], opt_.pulse_frames, opt_.seed);
            std::vector<Frame> field_frames(rs.size()), board_frames(rs.size());
            parallel_for(static_cast<int>(rs.size()), opt_.threads, [&](int i) {
                const auto at = static_cast<std::size_t>(i);
                const double op = pulsing_opacity(rs[at].index);
                field_frames[at] = shoot(scene_, rs[at], sim::mix_field(screens_[k], shown_, placement_, op), res);
                if (opt_.aruco) board_frames[at] = shoot(scene_, rs[at], methods_.board().mix(screens_[k], op), res);
            });
            std::vector<Outcome> u, v, a;
            run_methods(field_frames, board_frames, u, v, a);
            run.add(sim::to_string(sim::kEverydayScreenKinds[k]), std::move(u), std::move(v), std::move(a), minutes());
        }
        run.summarise_into(report_);
    }

    void write() {
        report_.wall_s = minutes() * 60;
        report_.settings["load_average_at_end"] = load_average();
        const std::filesystem::path dir(opt_.out);
        write_text(dir / "detector.json", to_json(report_).dump(2) + "\n");
        write_text(dir / "detector.md", to_markdown(report_));
        write_plots(report_, dir);
        std::cerr << "wrote " << (dir / "detector.md").string()
                  << ", detector.json, success_vs_opacity.png, ms_per_frame.png; total wall time " << report_.wall_s / 60
                  << " min (" << report_.wall_s << " s)\n";
    }

private:
    // Runs the methods on one sequence of frames on this thread, so that no
    // timed call shares the cores. umf and ArUco alternate frame by frame
    // (as before the tracker came); the tracker then gets the whole
    // sequence in its own pass, in order, so that it never finds its frame
    // in the cache from the single-frame call just before.
    void run_methods(const std::vector<Frame>& field_frames, const std::vector<Frame>& board_frames,
                     std::vector<Outcome>& umf_out, std::vector<Outcome>& video_out,
                     std::vector<Outcome>& aruco_out) const {
        for (std::size_t i = 0; i < field_frames.size(); ++i) {
            umf_out.push_back(methods_.umf(field_frames[i]));
            if (opt_.aruco) aruco_out.push_back(methods_.aruco(board_frames[i]));
        }
        if (!opt_.video) return;
        FrameClock clock(opt_.realtime, sim::kFps);
        Tracker tracker = methods_.tracker(clock.machine_ms(opt_.frame_share));
        for (std::size_t i = 0; i < field_frames.size(); ++i)
            video_out.push_back(methods_.video(tracker, field_frames[i], clock, static_cast<int>(i)));
    }

    // Makes the frames on all threads, then runs the methods one frame at a
    // time on this thread, so that no timed call shares the cores.
    void configuration(Category category, const std::vector<FrameRecipe>& rs, double opacity, cv::Size res,
                       const std::vector<cv::Mat>& with_field, const std::vector<cv::Mat>& with_board) {
        std::vector<Frame> field_frames(rs.size()), board_frames(rs.size());
        // Made ready per configuration, not per opacity, so that only one
        // category's renderings are kept (the pixel grid's are large).
        const auto field_sources = sim::screen_sources(with_field, scene_.screen);
        const auto board_sources =
            opt_.aruco ? sim::screen_sources(with_board, scene_.screen) : std::vector<sim::ScreenSource>{};
        parallel_for(static_cast<int>(rs.size()), opt_.threads, [&](int i) {
            const auto at = static_cast<std::size_t>(i);
            const auto kind = static_cast<std::size_t>(rs[at].screen);
            field_frames[at] = shoot(scene_, rs[at], field_sources[kind], res);
            if (opt_.aruco) board_frames[at] = shoot(scene_, rs[at], board_sources[kind], res);
        });
        ConfigResult cr;
        cr.category = to_string(category);
        cr.opacity = opacity;
        cr.resolution = resolution_name(res);
        if (!opt_.dump.empty()) dump(cr, field_frames, board_frames);

        ConfigOutcomes outcomes;
        run_methods(field_frames, board_frames, outcomes.umf, outcomes.video, outcomes.aruco);
        std::vector<std::string> kinds;
        for (const auto& r : rs) kinds.emplace_back(sim::to_string(r.screen));
        record_configuration(report_, cr, opacity, field_frames, kinds, outcomes,
                             is_plain(category));
        report_.configs.push_back(std::move(cr));
    }

    void dump(const ConfigResult& cr, const std::vector<Frame>& field_frames, const std::vector<Frame>& board_frames) const {
        std::filesystem::create_directories(opt_.dump);
        for (std::size_t i = 0; i < field_frames.size(); ++i) {
            const std::string stem = opt_.dump + "/" + cr.category + "_" +
                                     std::to_string(static_cast<int>(std::lround(cr.opacity * 100))) + "_" +
                                     cr.resolution + "_" + std::to_string(i);
            write_png(stem + "_umf.png", field_frames[i].grey);
            if (opt_.aruco) write_png(stem + "_aruco.png", board_frames[i].grey);
        }
    }

    std::string progress(const ConfigResult& cr) const {
        std::ostringstream o;
        o << cr.category << " opacity " << cr.opacity << " " << cr.resolution << ": umf " << short_result(cr.methods.at("umf"));
        if (opt_.video) o << " | umf video " << short_result(cr.methods.at("umf_video"));
        if (opt_.aruco) o << " | ArUco " << short_result(cr.methods.at("aruco"));
        return o.str();
    }

    double minutes() const { return ms_between(start_, Clock::now()) / 60000; }

    const Options& opt_;
    const Clock::time_point start_ = Clock::now();
    const Scene scene_;
    const Field field_;
    const Field shown_;  // on the screen; field_ unless --shown-field
    const Methods methods_;
    const sim::FieldPlacement placement_{{0, 0}, scene_.module_px};
    std::vector<cv::Mat> screens_;
    Report report_;
};

int run_heldout_set(const Options& opt, const std::string& command) {
    HeldoutOptions h;
    h.frames = opt.frames;
    h.pulse_frames = opt.pulse_frames;
    h.out = opt.out;
    if (!opt.category_names.empty()) {
        h.categories.clear();
        for (const auto& name : opt.category_names) {
            const auto c = heldout_category_from_string(name);
            if (!c) throw std::invalid_argument("unknown held-out category '" + name + "'");
            h.categories.push_back(*c);
        }
    }
    h.resolutions = opt.resolutions;
    if (opt.opacities_given) h.opacities = opt.opacities;
    h.aruco = opt.aruco;
    h.video = opt.video;
    h.seed = opt.seed;
    h.threads = opt.threads;
    h.dump = opt.dump;
    h.field = opt.field;
    h.shown_field = opt.shown_field;
    h.command = command;
    h.without = opt.without;
    h.tracking = opt.tracking;
    h.detecting = opt.detecting;
    h.realtime = opt.realtime;
    h.frame_share = opt.frame_share;
    return run_heldout(h);
}

int run(const Options& opt, const std::string& command) {
    if (opt.heldout) return run_heldout_set(opt, command);
    // OpenCV's own threads would compete with the frame-making threads and
    // would let ArUco use both cores where umf uses one.
    cv::setNumThreads(1);
    std::filesystem::create_directories(opt.out);
    Bench bench(opt, command);
    if (opt.frames > 0) bench.sweep();
    if (opt.pulse_frames > 0)
        for (cv::Size res : opt.resolutions) bench.pulsing(res);
    bench.write();
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string command = argv[0];
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    try {
        return run(parse(argc, argv), command);
    } catch (const std::exception& e) {
        std::cerr << "umf_benchmark: " << e.what() << "\n";
        return 1;
    }
}
