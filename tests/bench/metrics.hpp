// What the detector benchmark counts and how it reports it: per-frame
// outcomes of a method (umf single frame, umf video through the tracker,
// ArUco), their aggregate over one configuration (category x
// opacity x resolution), the gaps between successes in the pulsing video,
// and the JSON and Markdown reports. No OpenCV here: numbers in, text out.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace umf::bench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A located point counts as right within one module (30 screen px) of the
// truth: the aim then lies on the right module or its neighbour.
inline constexpr double kSuccessRadiusModules = 1.0;
inline constexpr const char* kWrongPlace = "wrong place (found, error > 1 module)";

inline constexpr std::array<const char*, 6> kStageNames = {"edgels", "vanishing", "grid", "classify", "vote", "refine"};

// The methods, in report order: key (JSON, maps) and name in the tables.
struct MethodName {
    const char* key;
    const char* label;
};
inline constexpr std::array<MethodName, 3> kMethods = {{{"umf", "umf"}, {"umf_video", "umf video"}, {"aruco", "ArUco"}}};
std::string method_label(const std::string& key);

// One method on one frame.
struct Outcome {
    bool skipped = false;  // the image centre is off the screen: there is no right answer
    bool found = false;
    double error_modules = kNaN;  // distance of the located aim point from the truth, when found
    double ms = 0;                // the method's call on one thread
    double pixels_pct = kNaN;     // share of the image's pixels read; NaN when the method does not say
    std::string failure;          // why not found; empty when found
    std::array<double, kStageNames.size()> stage_ms{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};  // see kStageNames; umf methods only
    double radius_modules = kSuccessRadiusModules;  // success radius of the set the frame belongs to

    bool success() const { return found && error_modules <= radius_modules; }
    bool false_location() const { return found && !(error_modules <= radius_modules); }
};

// One method over one configuration. Percentages are of the evaluated
// (not skipped) frames; errors are over the found frames; times over the
// evaluated frames.
struct Summary {
    int frames = 0, skipped = 0, evaluated = 0, found = 0, success = 0, false_location = 0;
    double success_pct = kNaN, false_pct = kNaN;
    double err_median = kNaN, err_p95 = kNaN;
    std::vector<double> false_errors;  // modules: how far off each false location was (a bent aim or a wrong place)
    double ms_median = kNaN, ms_mean = kNaN;
    double pixels_median_pct = kNaN;
    std::array<double, kStageNames.size()> stage_median_ms{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
    // Why frames were not successes: the method's failure strings, and
    // kWrongPlace for false locations.
    std::map<std::string, int> reasons;
};

Summary summarise(const std::vector<Outcome>& outcomes);

// Linear interpolation between order statistics; NaN for no values.
double percentile(std::vector<double> values, double p);

struct ConfigResult {
    std::string category;
    double opacity = 0;
    std::string resolution;                  // "640x480"
    std::map<std::string, Summary> methods;  // keys of kMethods
    // Image px per 30 px module at the image centre over the evaluated
    // frames: min, median, max (how near the camera was).
    std::array<double, 3> module_px{kNaN, kNaN, kNaN};
};

// The pulsing video: which frames each method located correctly, one
// sequence per screen kind.
struct PulseSummary {
    std::string method, resolution;
    int sequences = 0, frames = 0, skipped = 0, successes = 0, false_locations = 0;
    double success_pct = kNaN, false_pct = kNaN;  // of all frames, skipped ones included
    std::vector<double> false_errors;             // modules: how far off each false location was
    std::vector<int> gaps;  // frames from one success to the next, within each sequence
    double gaps_le3_pct = kNaN, gaps_le5_pct = kNaN, gap_median = kNaN;
    int gap_max = 0;
    // The longest run of frames without a success, counting the runs before
    // the first and after the last one, which gaps leave out.
    int longest_miss = 0;
    std::map<std::string, double> success_pct_by_screen;
};

// `outcomes[s][i]`: sequence s (screen kind screens[s]), frame i. Skipped
// frames (centre off the screen) count as misses for the gaps: the user
// sees no position there either.
PulseSummary summarise_pulse(const std::string& method, const std::string& resolution,
                             const std::vector<std::string>& screens,
                             const std::vector<std::vector<Outcome>>& outcomes);

// Success pooled over many configurations, split by one property of the
// frame: the module's size in the image, or the screen content.
struct Tally {
    int evaluated = 0, success = 0, false_location = 0;
};
inline constexpr std::array<double, 8> kModulePxBins = {0, 8, 12, 16, 24, 32, 48, 1e9};
int module_px_bin(double module_px);  // index into kModulePxBins, the bin's lower edge
std::string module_px_bin_label(int bin);
// method -> opacity -> bin or screen kind -> counts
using ModuleBreakdown = std::map<std::string, std::map<double, std::map<int, Tally>>>;
using ScreenBreakdown = std::map<std::string, std::map<double, std::map<std::string, Tally>>>;

struct Report {
    // Set for the held-out set (bench/heldout_run.cpp); empty or default for
    // the tuning set, whose report reads as it always has.
    std::string title;     // the Markdown heading
    std::string setup_md;  // replaces the tuning set's setup paragraph
    std::string json_name = "detector.json";
    double success_radius_modules = kSuccessRadiusModules;
    std::string pooled_over;                // what (f) and (g) pool, when not the tuning set's
    std::vector<std::string> screen_kinds;  // rows of (g) and columns of (c), when not the tuning set's
    std::string pulse_setup_md;             // replaces the tuning set's description of its pulsing video
    std::string command;
    std::string started;  // local date and time
    double wall_s = 0;
    nlohmann::json settings;
    std::vector<ConfigResult> configs;
    std::vector<PulseSummary> pulsing;
    // Every evaluated frame of a method at one resolution, over all
    // categories and opacities: method -> resolution -> ms per frame.
    std::map<std::string, std::map<std::string, std::vector<double>>> all_ms;
    // Over the five motion categories (not occlusion and low_light, whose
    // own effects would blur what size and content do), all resolutions.
    ModuleBreakdown by_module_px;
    ScreenBreakdown by_screen;
};

// The pulsing videos of one resolution as they are run: each video's
// outcomes per method, a line on stderr for each, then their summaries.
class PulseRun {
public:
    PulseRun(std::string resolution, bool video, bool aruco)
        : resolution_(std::move(resolution)), video_(video), aruco_(aruco) {}
    // One video on screen content `kind`; `minutes` since the run began.
    void add(const std::string& kind, std::vector<Outcome> umf, std::vector<Outcome> video, std::vector<Outcome> aruco,
             double minutes);
    // summarise_pulse of each method that was run, into report.pulsing.
    void summarise_into(Report& report) const;

private:
    std::string resolution_;
    bool video_, aruco_;
    std::vector<std::string> kinds_;
    std::vector<std::vector<Outcome>> umf_, video_out_, aruco_out_;
};

// Counts one evaluated frame of `method` into the report's breakdowns.
void tally(Report& report, const std::string& method, double opacity, double module_px, const std::string& screen,
           const Outcome& outcome);

nlohmann::json to_json(const Report& report);
std::string to_markdown(const Report& report);

}  // namespace umf::bench
