// The frames umf_speed_benchmark times: the tuning set's scenes
// (scenario.hpp) or the held-out set's (heldout_scenario.hpp), each category
// shot with the field, without it and with ArUco's board in its place, made
// once per resolution.
#pragma once

#include <opencv2/core.hpp>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "shared/detect/tracker.hpp"
#include "tests/bench/aruco_baseline.hpp"
#include "tests/bench/heldout_run.hpp"
#include "tests/bench/heldout_scenario.hpp"
#include "tests/bench/methods.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"

namespace umf::bench {

struct SpeedOptions {
    int frames = 20;          // per category
    double opacity = 0.3;
    int runs = 3;             // each call timed this many times; its median counts
    std::uint64_t seed = 1;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<cv::Size> resolutions{{640, 480}, {1280, 720}};
    std::string original_field = UMF_ORIGINAL_FIELD;
    std::string dump;  // also write the frames as PGM here
    bool parts = false;  // the search schedule's parts instead
    bool heldout = false;  // the held-out set's scenes instead of the tuning set's
    bool profile = false;  // only single frames with the field, for a profiler's view of the detector
    double frame_ms = 2;   // the time a frame's search is held to in the "held" rows (TrackerOptions::frame_ms)
    double first_scan_times = umf::TrackerOptions{}.first_scan_times;  // in the "held" rows
    bool held_only = false;  // only the rows of a tracker held to frame_ms
};

// Where the field is on the screen, to judge a located point.
struct Truth {
    sim::FieldPlacement placement;
    double radius_modules;
};

// One category's frames at one resolution: with the field, the content
// alone, with ArUco's board; consecutive, so that the tracker can follow
// them. Per frame, where the field is and the ArUco board it shows.
struct Clip {
    std::string category;
    std::vector<Frame> field, bare, board;
    std::vector<Truth> truth;
    std::vector<const ArucoBaseline*> aruco;
};

// The tuning set's scenes on its 1920 x 1080 screen, its contents made once.
class Frames {
public:
    explicit Frames(const SpeedOptions& opt) : opt_(opt), aruco_(scene_.screen.pixels, 30) {
        screens_.resize(sim::kAllScreenKinds.size());
        parallel_for(static_cast<int>(screens_.size()), opt.threads, [&](int k) {
            screens_[static_cast<std::size_t>(k)] =
                sim::make_screen(sim::kAllScreenKinds[static_cast<std::size_t>(k)], scene_.screen.pixels, 7);
        });
    }

    // The tuning set's clips, with `shown` on the screen at `placement`; a
    // place found counts as right within `radius` modules of the truth.
    std::vector<Clip> tuning(cv::Size res, const Field& shown, const sim::FieldPlacement& placement, double radius,
                             const std::vector<Category>& categories) const {
        std::vector<cv::Mat> with_field(screens_.size()), with_board(screens_.size());
        parallel_for(static_cast<int>(screens_.size()), opt_.threads, [&](int k) {
            const auto i = static_cast<std::size_t>(k);
            with_field[i] = sim::mix_field(screens_[i], shown, placement, opt_.opacity);
            with_board[i] = aruco_.mix(screens_[i], opt_.opacity);
        });
        std::vector<Clip> clips;
        for (Category c : categories) {
            const auto rs = category_recipes(scene_, c, opt_.frames, opt_.seed);
            Clip clip{to_string(c),
                      std::vector<Frame>(rs.size()),
                      std::vector<Frame>(rs.size()),
                      std::vector<Frame>(rs.size()),
                      std::vector<Truth>(rs.size(), Truth{placement, radius}),
                      std::vector<const ArucoBaseline*>(rs.size(), &aruco_)};
            // Made ready per category, so that only one category's renderings are kept.
            const auto field_sources = sim::screen_sources(with_field, scene_.screen);
            const auto bare_sources = sim::screen_sources(screens_, scene_.screen);
            const auto board_sources = sim::screen_sources(with_board, scene_.screen);
            parallel_for(static_cast<int>(rs.size()), opt_.threads, [&](int i) {
                const auto at = static_cast<std::size_t>(i);
                const auto kind = static_cast<std::size_t>(rs[at].screen);
                clip.field[at] = shoot(scene_, rs[at], field_sources[kind], res);
                clip.bare[at] = shoot(scene_, rs[at], bare_sources[kind], res);
                clip.board[at] = shoot(scene_, rs[at], board_sources[kind], res);
            });
            clips.push_back(std::move(clip));
        }
        return clips;
    }

    const Scene& scene() const { return scene_; }

private:
    const SpeedOptions& opt_;
    Scene scene_;
    ArucoBaseline aruco_;
    std::vector<cv::Mat> screens_;
};

// The held-out set's scenes (heldout_scenario.hpp): its three screens, each
// with its five contents, the field across each screen's width and ArUco's
// board with cells of one module; made once, as umf_benchmark --set heldout
// makes them.
class HeldoutFrames {
public:
    HeldoutFrames(const SpeedOptions& opt, const Field& field) : opt_(opt), field_(field) {
        for (const HeldoutScreen& s : heldout_screens()) {
            placements_.push_back(heldout_placement(s, field));
            aruco_.push_back(std::make_unique<ArucoBaseline>(
                s.geometry.pixels, static_cast<int>(std::lround(placements_.back().module_px))));
        }
        const std::size_t contents = sim::kAllHeldoutContents.size();
        screens_.resize(heldout_screens().size() * contents);
        parallel_for(static_cast<int>(screens_.size()), opt.threads, [&](int k) {
            const auto i = static_cast<std::size_t>(k);
            screens_[i] = sim::make_heldout_screen(sim::kAllHeldoutContents[i % contents],
                                                   heldout_screens()[i / contents].geometry.pixels, kHeldoutScreenSeed);
        });
    }

    std::vector<Clip> clips(cv::Size res) const {
        const std::size_t contents = sim::kAllHeldoutContents.size();
        std::vector<cv::Mat> with_field(screens_.size()), with_board(screens_.size());
        parallel_for(static_cast<int>(screens_.size()), opt_.threads, [&](int k) {
            const auto i = static_cast<std::size_t>(k);
            with_field[i] = sim::mix_field(screens_[i], field_, placements_[i / contents], opt_.opacity);
            with_board[i] = aruco_[i / contents]->mix(screens_[i], opt_.opacity);
        });
        const cv::Size modules(field_.width, field_.height);
        std::vector<Clip> clips;
        for (HeldoutCategory c : kAllHeldoutCategories) {
            const auto rs = heldout_recipes(c, opt_.frames, opt_.seed);
            const std::size_t n = rs.size();
            Clip clip{to_string(c), std::vector<Frame>(n), std::vector<Frame>(n), std::vector<Frame>(n),
                      std::vector<Truth>(n), std::vector<const ArucoBaseline*>(n)};
            parallel_for(static_cast<int>(n), opt_.threads, [&](int i) {
                const auto at = static_cast<std::size_t>(i);
                const auto s = static_cast<std::size_t>(rs[at].screen);
                const std::size_t k = s * contents + static_cast<std::size_t>(rs[at].content);
                clip.field[at] = shoot_heldout(rs[at], with_field[k], res, placements_[s], modules);
                clip.bare[at] = shoot_heldout(rs[at], screens_[k], res, placements_[s], modules);
                clip.board[at] = shoot_heldout(rs[at], with_board[k], res, placements_[s], modules);
                clip.board[at].centre_on_screen = clip.field[at].centre_on_screen;
                clip.truth[at] = Truth{placements_[s], kHeldoutRadiusModules};
                clip.aruco[at] = aruco_[s].get();
            });
            clips.push_back(std::move(clip));
        }
        return clips;
    }

private:
    const SpeedOptions& opt_;
    const Field& field_;
    std::vector<sim::FieldPlacement> placements_;
    std::vector<std::unique_ptr<ArucoBaseline>> aruco_;
    std::vector<cv::Mat> screens_;
};

}  // namespace umf::bench
