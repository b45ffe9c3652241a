// umf_speed_benchmark: how fast the detector is, on frames made once and
// timed one call at a time on one thread: single frames with the field and
// without it (the content alone, what a phone sees while it is raised
// towards the screen), the tracker over each category's frames in order,
// ArUco on the same scenes with its board in place of the field, and the
// detector on a field of the method's original authors. The tuning set's
// scenes, or the held-out set's (heldout_scenario.hpp: other screens,
// contents and camera). Prints Markdown tables and the per-stage profile;
// docs/BENCHMARKS.md keeps them.
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "tests/bench/part_order.hpp"
#include "tests/bench/speed_frames.hpp"

namespace umf::bench {
namespace {

struct Timing {
    std::vector<double> ms;
    int found = 0, right = 0, wrong = 0, frames = 0;
    StageTimes stages;
};

double median_of(std::vector<double> v) { return percentile(std::move(v), 50); }

void add_stages(StageTimes& sum, const StageTimes& t) {
    sum.edgels_ms += t.edgels_ms, sum.vanishing_ms += t.vanishing_ms, sum.grid_ms += t.grid_ms;
    sum.classify_ms += t.classify_ms, sum.vote_ms += t.vote_ms, sum.refine_ms += t.refine_ms;
    sum.total_ms += t.total_ms;
}

void judge(Timing& t, const Frame& f, bool found, const Eigen::Vector2d& aim_field, const Truth* truth) {
    ++t.frames;
    if (!found) return;
    ++t.found;
    if (!truth || !f.centre_on_screen) {
        ++t.wrong;  // a place where there is none
        return;
    }
    const cv::Point2d aim = sim::field_to_screen(truth->placement, {aim_field.x(), aim_field.y()});
    (cv::norm(aim - f.centre_screen_px) / truth->placement.module_px <= truth->radius_modules ? t.right : t.wrong)++;
}

// A call timed `runs` times; the median counts.
template <class Call>
double timed(int runs, const Call& call) {
    std::vector<double> ms;
    for (int r = 0; r < runs; ++r) {
        const auto t0 = BenchClock::now();
        call();
        ms.push_back(ms_between(t0, BenchClock::now()));
    }
    return median_of(ms);
}

// The clip's frames with the field (judged against the truth), or without it
// (every place found is wrong).
Timing time_single(const Detector& detector, const Clip& clip, bool with_field, int runs) {
    Timing t;
    const std::vector<Frame>& frames = with_field ? clip.field : clip.bare;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Frame& f = frames[i];
        if (with_field && !f.centre_on_screen) continue;
        Detection d;
        t.ms.push_back(timed(runs, [&] { d = detector.detect(grey_view(f)); }));
        add_stages(t.stages, d.times);
        judge(t, f, d.found, d.aim_field, with_field ? &clip.truth[i] : nullptr);
    }
    return t;
}

// Each share of the spread search's round (search_schedule at the
// tracker's default budget) on each frame without the field: what a frame
// costs a tracker that has not found the field for a while, whichever share
// it is at (the tracker's own row takes them in the order it runs them, at
// the same fixed budget).
Timing time_shares(const Detector& detector, const Clip& clip, int runs) {
    Timing t;
    const double budget = TrackerOptions{}.search_budget;
    for (const Frame& f : clip.bare) {
        const GreyView v = grey_view(f);
        const Eigen::Vector2d centre(v.width / 2.0, v.height / 2.0);
        for (int k = 0; k < schedule_frames(budget); ++k) {
            const ScheduledSearch share = search_schedule(k, budget);
            Detection d;
            t.ms.push_back(timed(runs, [&] {
                d = detector.detect(v, centre, nullptr, std::span<const SearchPlan>(share.plans.data(), share.count));
            }));
            judge(t, f, d.found, d.aim_field, nullptr);
        }
    }
    return t;
}

// The tracker over the clip in order, `passes` times over with the same
// tracker (its state moves on with every frame); frames whose centre is off
// the field are given to it but not counted, as a phone keeps filming then
// too.
Timing time_tracker(const Detector& detector, const Clip& clip, bool with_field, const TrackerOptions& options,
                    int passes = 1) {
    Timing t;
    Tracker tracker(detector, options);
    const std::vector<Frame>& frames = with_field ? clip.field : clip.bare;
    for (int pass = 0; pass < passes; ++pass)
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const Frame& f = frames[i];
            TrackResult r;
            const double ms = timed(1, [&] { r = tracker.update(grey_view(f)); });
            if (!f.centre_on_screen) continue;
            t.ms.push_back(ms);
            judge(t, f, r.state == TrackState::locked, r.aim_field, with_field ? &clip.truth[i] : nullptr);
        }
    return t;
}

TrackerOptions spreading(double frame_ms = 0, bool hold_first_scan = false,
                         double first_scan_times = TrackerOptions{}.first_scan_times) {
    TrackerOptions o;
    o.spread_search = true;
    o.frame_ms = frame_ms;
    o.hold_first_scan = hold_first_scan;
    o.first_scan_times = first_scan_times;
    return o;
}

Timing time_aruco(const Clip& clip, int runs) {
    Timing t;
    for (std::size_t i = 0; i < clip.board.size(); ++i) {
        const Frame& f = clip.board[i];
        if (!f.centre_on_screen) continue;
        ArucoLocation a;
        t.ms.push_back(timed(runs, [&] { a = clip.aruco[i]->locate(f.grey); }));
        ++t.frames;
        if (a.found) ++t.found;
    }
    return t;
}

void merge(Timing& into, const Timing& t) {
    into.ms.insert(into.ms.end(), t.ms.begin(), t.ms.end());
    into.found += t.found, into.right += t.right, into.wrong += t.wrong, into.frames += t.frames;
    add_stages(into.stages, t.stages);
}

std::string fixed(double v, int digits = 2) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

std::string row(const std::string& name, const Timing& t, bool judged = true) {
    if (t.ms.empty()) return "| " + name + " | 0 | | | | |\n";
    const double max = *std::max_element(t.ms.begin(), t.ms.end());
    std::string found = std::to_string(t.found) + " of " + std::to_string(t.frames);
    if (judged) found += " (" + std::to_string(t.wrong) + " wrong)";
    return "| " + name + " | " + found + " | " + fixed(median_of(t.ms)) + " | " + fixed(percentile(t.ms, 95)) +
           " | " + fixed(max, 1) + " |\n";
}

std::string stage_profile(const StageTimes& s) {
    const std::pair<const char*, double> stages[] = {
        {"edgels (and resizing)", s.edgels_ms}, {"vanishing points", s.vanishing_ms},
        {"grid lines, homography, lattice", s.grid_ms}, {"reading modules", s.classify_ms},
        {"window vote", s.vote_ms}, {"refit and aim", s.refine_ms}};
    double named = 0;
    std::string out;
    for (const auto& [name, ms] : stages) {
        named += ms;
        out += std::string(name) + " " + fixed(s.total_ms > 0 ? 100 * ms / s.total_ms : 0, 0) + " %, ";
    }
    out += "the rest " + fixed(s.total_ms > 0 ? 100 * (s.total_ms - named) / s.total_ms : 0, 0) + " %";
    return out;
}

void dump_clips(const std::string& dir, const std::string& prefix, const std::vector<Clip>& clips) {
    std::filesystem::create_directories(dir);
    for (const Clip& c : clips)
        for (std::size_t i = 0; i < c.field.size(); ++i) {
            const std::string stem = dir + "/" + prefix + "-" + c.category + "-" + std::to_string(i);
            cv::imwrite(stem + "-field.pgm", c.field[i].grey);
            cv::imwrite(stem + "-bare.pgm", c.bare[i].grey);
        }
}

std::string resolution_name(cv::Size r) { return std::to_string(r.width) + " x " + std::to_string(r.height); }

// The detector's order (kPartOrder) against the greedy one, over `sets`.
std::string order_comparison(const std::vector<PartFinds>& sets) {
    const std::vector<int> ours(kPartOrder.begin(), kPartOrder.end()), greedy = greedy_order(sets);
    int unfound = 0;
    for (const PartFinds& set : sets) unfound += static_cast<int>(std::count(set.found_by.begin(), set.found_by.end(), 0u));
    return "Mean time to find a frame the first scan misses, from the parts' median costs (" + std::to_string(unfound) +
           " found by none): the detector's order (" + order_text(ours) + ") " +
           fixed(mean_time_to_find(ours, sets)) + " ms; greedy (" + order_text(greedy) + ") " +
           fixed(mean_time_to_find(greedy, sets)) + " ms.\n";
}

// Each part of the search (search_plan.hpp) alone: its time on frames
// without the field, and the frames with it that the part finds where the
// first scan does not; then the detector's order of the parts against the
// greedy one. `finds` gains this resolution's.
std::string schedule_parts(const Detector& detector, const std::vector<Clip>& clips, std::vector<PartFinds>& finds) {
    std::string out = "| part (search_part) | median ms without the field | p95 | finds, of the frames the first scan "
                      "misses |\n|---|---|---|---|\n";
    int found_by_first = 0;
    std::vector<unsigned> found_by;  // per frame the first scan misses: the parts that find it, as bits
    std::map<int, std::vector<double>> ms;
    for (const Clip& c : clips) {
        for (const Frame& f : c.field) {
            if (!f.centre_on_screen) continue;
            const Eigen::Vector2d centre(f.grey.cols / 2.0, f.grey.rows / 2.0);
            if (detector.detect(grey_view(f), centre, nullptr, first_scan_only()).found) {
                ++found_by_first;
                continue;
            }
            unsigned mask = 0;
            for (int k = 0; k < kSearchParts; ++k)
                if (detector.detect(grey_view(f), centre, nullptr, search_part(k)).found) mask |= 1u << k;
            found_by.push_back(mask);
        }
        for (const Frame& f : c.bare) {
            const Eigen::Vector2d centre(f.grey.cols / 2.0, f.grey.rows / 2.0);
            for (int k = -1; k < kSearchParts; ++k) {
                const SearchPlan plan = k < 0 ? first_scan_only() : search_part(k);
                ms[k].push_back(timed(1, [&] { detector.detect(grey_view(f), centre, nullptr, plan); }));
            }
        }
    }
    std::map<int, double> cost;
    for (const auto& [k, v] : ms) {
        cost[k] = median_of(v);
        int finds = 0;
        for (unsigned m : found_by) finds += k >= 0 && ((m >> k) & 1u);
        out += "| " + (k < 0 ? std::string("the first scan") : std::to_string(k)) + " | " + fixed(cost[k]) + " | " +
               fixed(percentile(v, 95)) + " | " +
               (k < 0 ? std::to_string(found_by_first) + " found"
                      : std::to_string(finds) + " of " + std::to_string(found_by.size())) +
               " |\n";
    }
    std::map<int, double> part_cost(cost);
    part_cost.erase(-1);
    finds.push_back({found_by, part_cost});
    out += "\n" + order_comparison({finds.back()});
    return out;
}

// The rows of a tracker held to opt.frame_ms (its first scan whole, and
// held too), over each clip with the field and three times over it without
// (a phone raised towards the screen films it for a while).
struct HeldTimings {
    Timing whole_first, whole_first_bare, held_first, held_first_bare;

    void add(const Detector& detector, const Clip& c, const SpeedOptions& opt) {
        merge(whole_first, time_tracker(detector, c, true, spreading(opt.frame_ms)));
        merge(whole_first_bare, time_tracker(detector, c, false, spreading(opt.frame_ms), 3));
        merge(held_first, time_tracker(detector, c, true, spreading(opt.frame_ms, true, opt.first_scan_times)));
        merge(held_first_bare,
              time_tracker(detector, c, false, spreading(opt.frame_ms, true, opt.first_scan_times), 3));
    }

    std::string rows(const SpeedOptions& opt) const {
        const std::string ms = fixed(opt.frame_ms, 1), times = fixed(opt.first_scan_times, 1);
        return row("with the field, tracker held to " + ms + " ms a frame", whole_first) +
               row("without the field, tracker held to " + ms + " ms a frame (three times over)", whole_first_bare) +
               row("with the field, the first scan held too, to " + times +
                       " times that (TrackerOptions::hold_first_scan)",
                   held_first) +
               row("without the field, the first scan held too (three times over)", held_first_bare);
    }
};

// The tables of one resolution.
std::string time_resolution(const Detector& detector, const std::vector<Clip>& clips, const SpeedOptions& opt) {
    Timing with_all, bare_all, video_all, video_bare_all, spread_all, spread_bare_all, shares_all, aruco_all;
    HeldTimings held;
    std::string per_category;
    if (opt.profile) {
        for (const Clip& c : clips) merge(with_all, time_single(detector, c, true, opt.runs));
        return row("with the field, single frame", with_all) + "\n";
    }
    const std::string header = "| frames | found | median ms | p95 ms | max ms |\n|---|---|---|---|---|\n";
    if (opt.held_only) {
        for (const Clip& c : clips) held.add(detector, c, opt);
        return header + held.rows(opt) + "\n";
    }
    for (const Clip& c : clips) {
        const Timing with = time_single(detector, c, true, opt.runs);
        const Timing bare = time_single(detector, c, false, opt.runs);
        const Timing video = time_tracker(detector, c, true, TrackerOptions{});
        const Timing video_bare = time_tracker(detector, c, false, TrackerOptions{});
        merge(spread_all, time_tracker(detector, c, true, spreading()));
        merge(spread_bare_all, time_tracker(detector, c, false, spreading()));
        merge(shares_all, time_shares(detector, c, 1));
        held.add(detector, c, opt);
        const Timing aruco = time_aruco(c, opt.runs);
        auto cell = [](const Timing& t) { return fixed(median_of(t.ms)) + " / " + fixed(percentile(t.ms, 95)); };
        per_category += "| " + c.category + " | " + cell(with) + " | " + cell(bare) + " | " + cell(video) + " | " +
                        cell(video_bare) + " | " + fixed(median_of(aruco.ms)) + " | " + std::to_string(with.right) +
                        " / " + std::to_string(video.right) + " of " + std::to_string(with.frames) + " |\n";
        merge(with_all, with), merge(bare_all, bare), merge(video_all, video), merge(video_bare_all, video_bare);
        merge(aruco_all, aruco);
    }
    std::ostringstream out;
    out << header << row("with the field, single frame", with_all) << row("without the field, single frame", bare_all)
        << row("with the field, tracker", video_all) << row("without the field, tracker", video_bare_all)
        << row("with the field, tracker spreading its search", spread_all)
        << row("without the field, tracker spreading its search", spread_bare_all)
        << row("without the field, each share of the spread search (" +
                   std::to_string(schedule_frames(TrackerOptions{}.search_budget)) + " a round) on each frame",
               shares_all)
        << held.rows(opt)
        << row("ArUco, its board in place of the field", aruco_all, false)
        << "\nArUco's median over umf's: single frame " << fixed(median_of(aruco_all.ms) / median_of(with_all.ms))
        << " x, tracker " << fixed(median_of(aruco_all.ms) / median_of(video_all.ms)) << " x.\n\n"
        << "Per category, median / p95 ms, and the frames found right (single frame / tracker):\n\n"
        << "| category | with the field | without | tracker | tracker without | ArUco median | right |\n"
        << "|---|---|---|---|---|---|---|\n"
        << per_category << "\nWhere single frames with the field spend their time: " << stage_profile(with_all.stages)
        << ".\n\nWithout the field: " << stage_profile(bare_all.stages) << ".\n\n";
    return out.str();
}

// The authors' 19 x 31 field (five shades, 3 x 3 edge windows) across the
// tuning screen's height, centred: general and perspective at 640 x 480.
std::string time_original_field(const Frames& frames, const SpeedOptions& opt) {
    const Field original = load_field(opt.original_field);
    const double module = static_cast<double>(frames.scene().screen.pixels.height) / original.height;
    const sim::FieldPlacement on_screen{
        {(frames.scene().screen.pixels.width - module * original.width) / 2, 0}, module};
    const Detector original_detector(original);
    Timing with_original;
    for (Clip& c : frames.tuning({640, 480}, original, on_screen, 1.0, {Category::general, Category::perspective})) {
        for (Frame& f : c.field) {
            const cv::Point2d uv = sim::screen_to_field(on_screen, f.centre_screen_px);
            f.centre_on_screen = f.centre_on_screen && uv.x >= 0 && uv.y >= 0 && uv.x <= original.width &&
                                 uv.y <= original.height;
        }
        merge(with_original, time_single(original_detector, c, true, opt.runs));
    }
    return "### The original authors' field (" + std::filesystem::path(opt.original_field).filename().string() +
           ", " + fixed(module, 1) + " px modules), 640 x 480, general and perspective\n\n" +
           "| frames | found | median ms | p95 ms | max ms |\n|---|---|---|---|---|\n" +
           row("with the field, single frame", with_original) + "\n";
}

int run(const SpeedOptions& opt) {
    const Field field = bench_field("b4-64x36.json");
    const Detector detector(field);
    std::optional<Frames> frames;
    std::optional<HeldoutFrames> heldout;
    if (opt.heldout) {
        heldout.emplace(opt, field);
        std::cout << "Frames: the held-out set's " << kAllHeldoutCategories.size() << " categories";
    } else {
        frames.emplace(opt);
        std::cout << "Frames: the tuning set's " << kAllCategories.size() << " categories";
    }
    std::cout << ", " << opt.frames << " consecutive frames each, field and board at opacity " << opt.opacity
              << ", seed " << opt.seed << "; each single-frame call timed " << opt.runs
              << " times (its median counts), the tracker once; one thread.\n\n";
    const std::vector<Category> categories(kAllCategories.begin(), kAllCategories.end());
    std::vector<PartFinds> finds;
    for (cv::Size res : opt.resolutions) {
        std::cerr << "making " << resolution_name(res) << " frames\n";
        const auto clips = heldout ? heldout->clips(res)
                                   : frames->tuning(res, field, {{0, 0}, frames->scene().module_px}, 1.0, categories);
        if (!opt.dump.empty())
            dump_clips(opt.dump,
                       std::string(heldout ? "heldout" : "tuning") + "-" + std::to_string(res.width) + "x" +
                           std::to_string(res.height),
                       clips);
        std::cerr << "timing " << resolution_name(res) << "\n";
        std::cout << "### " << resolution_name(res) << "\n\n"
                  << (opt.parts ? schedule_parts(detector, clips, finds) + "\n" : time_resolution(detector, clips, opt));
    }
    if (opt.parts && finds.size() > 1) std::cout << "### All resolutions\n\n" << order_comparison(finds);
    if (!opt.parts && !opt.profile && frames) std::cout << time_original_field(*frames, opt);
    return 0;
}

const char kUsage[] =
    "umf_speed_benchmark: the detector's time per frame on the tuning set's scenes (or the held-out set's), one "
    "call at a time on one thread.\n\n"
    "Usage: umf_speed_benchmark [options]\n"
    "  --set tuning|heldout   whose scenes (default tuning; the original authors' field with the tuning set only)\n"
    "  --frames N             consecutive frames per category (default 20)\n"
    "  --opacity A            field and board opacity (default 0.3)\n"
    "  --runs N               times each single-frame call is timed, its median counted (default 3)\n"
    "  --resolutions WxH,...  (default 640x480,1280x720)\n"
    "  --seed N               scenario seed (default 1)\n"
    "  --threads N            threads making frames (default: all cores)\n"
    "  --original-field FILE  the original authors' field (default tests/data/original-umf/sog5-19x31.json)\n"
    "  --dump DIR             also write the frames there as PGM (with the field and without), named\n"
    "                         SET-WxH-CATEGORY-N-field.pgm and -bare.pgm\n"
    "  --parts                instead: each part of the tracker's search schedule alone, its time on the frames\n"
    "                         without the field and the frames with it that it finds where the first scan does not\n"
    "  --frame-ms MS          the time a frame's search is held to in the \"held\" rows: the tracker's spread\n"
    "                         search as a phone runs it (TrackerOptions::frame_ms; default 2)\n"
    "  --first-scan-times X   in the \"first scan held too\" rows its time, X times --frame-ms\n"
    "                         (TrackerOptions::first_scan_times; default 2)\n"
    "  --held                 only the rows of a tracker held to --frame-ms\n"
    "  --profile              only single frames with the field (each --runs times), for a profiler\n"
    "  --help                 this text\n\n"
    "Progress goes to stderr, the tables to stdout.\n";

}  // namespace
}  // namespace umf::bench

int main(int argc, char** argv) {
    using namespace umf::bench;
    SpeedOptions opt;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
                return argv[++i];
            };
            if (a == "--help") {
                std::cout << kUsage;
                return 0;
            } else if (a == "--set") {
                const std::string set = value();
                if (set != "tuning" && set != "heldout") throw std::invalid_argument("--set: tuning or heldout");
                opt.heldout = set == "heldout";
            } else if (a == "--frames") {
                opt.frames = std::stoi(value());
            } else if (a == "--opacity") {
                opt.opacity = std::stod(value());
            } else if (a == "--runs") {
                opt.runs = std::max(1, std::stoi(value()));
            } else if (a == "--resolutions") {
                opt.resolutions = parse_resolutions(value());
            } else if (a == "--seed") {
                opt.seed = std::stoull(value());
            } else if (a == "--threads") {
                opt.threads = std::max(1, std::stoi(value()));
            } else if (a == "--original-field") {
                opt.original_field = value();
            } else if (a == "--frame-ms") {
                opt.frame_ms = std::stod(value());
                if (!(opt.frame_ms > 0)) throw std::invalid_argument("--frame-ms: a time above 0");
            } else if (a == "--first-scan-times") {
                opt.first_scan_times = std::stod(value());
                if (!(opt.first_scan_times > 0)) throw std::invalid_argument("--first-scan-times: a number above 0");
            } else if (a == "--held") {
                opt.held_only = true;
            } else if (a == "--profile") {
                opt.profile = true;
            } else if (a == "--parts") {
                opt.parts = true;
            } else if (a == "--dump") {
                opt.dump = value();
            } else {
                std::cerr << "unknown option " << a << "\n\n" << kUsage;
                return 2;
            }
        }
        return run(opt);
    } catch (const std::exception& e) {
        std::cerr << "umf_speed_benchmark: " << e.what() << "\n";
        return 1;
    }
}
