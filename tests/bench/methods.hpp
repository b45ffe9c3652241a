// The methods the detector benchmark compares, each turning a frame into an
// Outcome with its call timed and nothing else, and the thread pool that
// makes frames. Shared by the tuning and the held-out sets.
#pragma once

#include <opencv2/core.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
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
#include "tests/bench/frame_clock.hpp"
#include "tests/bench/metrics.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"

namespace umf::bench {

using BenchClock = std::chrono::steady_clock;

inline double ms_between(BenchClock::time_point a, BenchClock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// Runs job(i) for i in [0, n) on `threads` threads; the first exception is
// rethrown here.
template <class Job>
void parallel_for(int n, int threads, const Job& job) {
    std::atomic<int> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    std::vector<std::thread> pool;
    for (int t = 0; t < std::min(threads, n); ++t)
        pool.emplace_back([&] {
            try {
                for (int i; (i = next++) < n;) job(i);
            } catch (...) {
                std::lock_guard<std::mutex> lock(error_mutex);
                if (!error) error = std::current_exception();
                next = n;
            }
        });
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}


// A benchmark's field: a name in shared/data/fields, or a field file's path
// (one with a '/', such as a screen's own field).
inline Field bench_field(const std::string& name_or_path) {
    return load_field(name_or_path.find('/') != std::string::npos ? name_or_path
                                                                   : std::string(UMF_DATA_DIR) + "/fields/" + name_or_path);
}

// A benchmark's --resolutions: "WxH,WxH,...", each side at least 16 pixels.
inline std::vector<cv::Size> parse_resolutions(const std::string& list) {
    std::vector<cv::Size> out;
    std::stringstream in(list);
    for (std::string item; std::getline(in, item, ',');) {
        const auto x = item.find('x');
        int w = 0, h = 0;
        std::size_t used_w = 0, used_h = 0;
        try {
            if (x != std::string::npos) {
                w = std::stoi(item.substr(0, x), &used_w);
                h = std::stoi(item.substr(x + 1), &used_h);
            }
        } catch (const std::exception&) {
            used_w = used_h = 0;
        }
        if (x == std::string::npos || used_w != x || used_h != item.size() - x - 1 || w < 16 || h < 16)
            throw std::invalid_argument("--resolutions: '" + item + "' is not WxH with sides of 16 pixels or more");
        out.emplace_back(w, h);
    }
    if (out.empty()) throw std::invalid_argument("--resolutions: none given");
    return out;
}

// A frame's grey image as the detector takes it.
inline GreyView grey_view(const Frame& frame) {
    return {frame.grey.data, frame.grey.cols, frame.grey.rows, static_cast<std::ptrdiff_t>(frame.grey.step)};
}

// The methods under test, each turning a frame into an Outcome with its
// call timed and nothing else.
class Methods {
public:
    // The field at `placement` on a screen of `screen` pixels, the ArUco
    // board with cells of `board_cell_px`; a located point counts as right
    // within `radius_modules` of the truth.
    // `tracking`: the trackers' options (umf video); `detecting`: the
    // detector's (umf and umf video).
    Methods(const Field& field, cv::Size screen, sim::FieldPlacement placement, int board_cell_px, double radius_modules,
            TrackerOptions tracking = {}, DetectorOptions detecting = {})
        : placement_(placement),
          radius_(radius_modules),
          detector_(field, detecting),
          tracking_(tracking),
          aruco_(screen, board_cell_px) {}

    Outcome umf(const Frame& frame) const {
        Outcome o;
        o.radius_modules = radius_;
        if (!frame.centre_on_screen) {
            o.skipped = true;
            return o;
        }
        Detection d;
        const auto t0 = BenchClock::now();
        try {
            d = detector_.detect(grey_view(frame));
        } catch (const std::exception& e) {
            // The detector is work in progress: one bad frame should cost
            // that frame, not the whole run.
            d.found = false;
            d.failure = std::string("exception: ") + e.what();
        }
        const auto t1 = BenchClock::now();
        o.ms = ms_between(t0, t1);
        o.found = d.found;
        o.failure = d.failure;
        fill_umf(o, frame, d, d.aim_field);
        return o;
    }

    // A fresh tracker on this detector: one per configuration and per
    // pulsing video.
    // `frame_ms` > 0: its spread search fits its shares in that time
    // (TrackerOptions::frame_ms).
    Tracker tracker(double frame_ms = 0) const {
        TrackerOptions o = tracking_;
        if (frame_ms > 0) o.frame_ms = frame_ms;
        return Tracker(detector_, o);
    }

    // One frame of a video: every frame goes to the tracker (a phone keeps
    // filming while the centre is off the screen), but such frames are
    // marked skipped for the statistics.
    Outcome video(Tracker& tracker, const Frame& frame) const {
        Outcome o;
        o.radius_modules = radius_;
        TrackResult t;
        const auto t0 = BenchClock::now();
        try {
            t = tracker.update(grey_view(frame));
        } catch (const std::exception& e) {
            t = TrackResult{};
            t.state = TrackState::lost;
            t.detection.failure = std::string("exception: ") + e.what();
        }
        const auto t1 = BenchClock::now();
        o.ms = ms_between(t0, t1);  // also of a skipped frame: the real-time clock counts it
        if (!frame.centre_on_screen) {
            o.skipped = true;
            return o;
        }
        o.found = t.state == TrackState::locked;
        if (!o.found) o.failure = t.detection.failure.empty() ? to_string(t.state) : t.detection.failure;
        fill_umf(o, frame, t.detection, t.aim_field);
        return o;
    }

    // Frame `index` of a video watched in real time (frame_clock.hpp): the
    // tracker's outcome, or a dropped frame the tracker never sees.
    Outcome video(Tracker& tracker, const Frame& frame, FrameClock& clock, int index) const {
        if (!clock.free_for(index)) {
            Outcome o;
            o.radius_modules = radius_;
            o.skipped = !frame.centre_on_screen;
            o.ms = kNaN;  // no call: not in the time statistics
            o.failure = kDroppedFrame;
            return o;
        }
        Outcome o = video(tracker, frame);
        clock.took(index, o.ms);
        return o;
    }

    Outcome aruco(const Frame& frame) const {
        Outcome o;
        o.radius_modules = radius_;
        if (!frame.centre_on_screen) {
            o.skipped = true;
            return o;
        }
        ArucoLocation a;
        const auto t0 = BenchClock::now();
        try {
            a = aruco_.locate(frame.grey);
        } catch (const std::exception& e) {
            a.found = false;
            a.failure = std::string("exception: ") + e.what();
        }
        const auto t1 = BenchClock::now();
        o.ms = ms_between(t0, t1);
        o.found = a.found;
        o.failure = a.failure;
        if (a.found) o.error_modules = cv::norm(a.aim_screen_px - frame.centre_screen_px) / placement_.module_px;
        return o;
    }

    const ArucoBaseline& board() const { return aruco_; }
    const Field& field() const { return detector_.field(); }

private:
    // The umf methods' pixels, stage times and aim error (when found).
    void fill_umf(Outcome& o, const Frame& frame, const Detection& d, const Eigen::Vector2d& aim_field) const {
        o.pixels_pct = 100.0 * static_cast<double>(d.pixels_visited) / static_cast<double>(frame.grey.total());
        o.stage_ms = {d.times.edgels_ms, d.times.vanishing_ms, d.times.grid_ms,
                      d.times.classify_ms, d.times.vote_ms,      d.times.refine_ms};
        if (o.found) {
            const cv::Point2d aim = sim::field_to_screen(placement_, {aim_field.x(), aim_field.y()});
            o.error_modules = cv::norm(aim - frame.centre_screen_px) / placement_.module_px;
        }
    }

    sim::FieldPlacement placement_;
    double radius_;
    Detector detector_;
    TrackerOptions tracking_;
    ArucoBaseline aruco_;
};

// One configuration's outcomes per method, in frame order; video and aruco
// are empty when those methods were left out.
struct ConfigOutcomes {
    std::vector<Outcome> umf, video, aruco;
};

// What every configuration of either set records: each method's summary and
// the module sizes seen into `cr`; each frame's time into the report and,
// when `tally_frames`, its module size and screen kind (`kinds[i]`) into the
// report's breakdowns.
inline void record_configuration(Report& report, ConfigResult& cr, double opacity, const std::vector<Frame>& frames,
                                 const std::vector<std::string>& kinds, const ConfigOutcomes& o, bool tally_frames) {
    const std::pair<const char*, const std::vector<Outcome>*> methods[] = {
        {"umf", &o.umf}, {"umf_video", &o.video}, {"aruco", &o.aruco}};
    for (const auto& [name, out] : methods)
        if (!out->empty()) cr.methods[name] = summarise(*out);
    std::vector<double> module_px;
    for (const auto& f : frames)
        if (f.centre_on_screen) module_px.push_back(f.module_px_in_image);
    if (!module_px.empty())
        cr.module_px = {*std::min_element(module_px.begin(), module_px.end()), percentile(module_px, 50),
                        *std::max_element(module_px.begin(), module_px.end())};
    for (std::size_t i = 0; i < frames.size(); ++i)
        for (const auto& [name, out] : methods) {
            if (out->empty()) continue;
            const Outcome& outcome = (*out)[i];
            if (!outcome.skipped) report.all_ms[name][cr.resolution].push_back(outcome.ms);
            if (tally_frames) tally(report, name, opacity, frames[i].module_px_in_image, kinds[i], outcome);
        }
}

}  // namespace umf::bench
