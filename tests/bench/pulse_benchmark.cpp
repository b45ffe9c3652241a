// umf_pulse_benchmark: a field pulsing at a few percent of opacity, filmed
// by a hand-held phone, found by the tracker alone and by the tracker with
// the pulse search (shared/detect/pulse_tracker.hpp), frame by frame, and
// the same videos without the field, where every place found is wrong.
// docs/BENCHMARKS.md, "A field nobody notices".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "shared/detect/pulse_tracker.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/bench/heldout_run.hpp"
#include "tests/bench/heldout_scenario.hpp"
#include "tests/bench/methods.hpp"
#include "tests/bench/phone_effects.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/sequence.hpp"

namespace umf::bench {
namespace {

const char* const kUsage = R"(umf_pulse_benchmark: a field pulsing at a few percent found over a hand-held phone's frames.

Usage: umf_pulse_benchmark [options]
  --set tuning|heldout   whose pulsing videos (default tuning): the tuning set's swing from looking up at the
                         screen to looking down on it at 25 fps, one video per screen kind; or the held-out
                         set's hand path at 30 fps, one per content, on its three screens and camera model
  --opacities MIN,MAX    the pulse's opacities (default 0.01,0.04), sine, every 1.5 s
  --frames N             frames per video (default 150)
  --resolutions WxH,...  (default 640x480)
  --not-announced        the pulse search is not told the pulse's period, waveform and opacities
  --frame-ms MS          the tracker's search held to MS a frame, as the page holds it (TrackerOptions::frame_ms
                         with its spread search; default 2); 0: every search on every frame without a lock
  --max-motion-change X  PulseSearchOptions::max_motion_change (default: the library's)
  --max-follow-shape-change X
                         PulseSearchOptions::max_follow_shape_change, modules (default: the library's; 1e9:
                         a follow's map always carried on)
  --exposure-drift A     the tuning set's videos with an auto-exposure that drifts and re-meters, the light
                         scaled by up to about 1 +- A from frame to frame (default 0: a steady exposure)
  --rolling-shutter S    the tuning set's videos read row by row over S seconds (first row to last, the
                         middle row at the frame's own pose), the camera moving on towards the next frame's
                         pose meanwhile (default 0: every row at once)
  --swing-speed K        the tuning set's hand swinging K times as fast (an integer; default 1)
  --noise S              the tuning set's sensor noise, S grey levels (default: 2 to 3 a frame)
  --jpeg-quality Q       the tuning set's frames encoded at JPEG quality Q (default 80)
  --gain                 the frames registered with the exposure's gain as well as a grey-level offset
                         (RegistrationOptions::fit_gain)
  --no-levelling         the frames laid onto the newest not levelled to its exposure before demodulating
                         (PulseSearchOptions::level_exposure off)
  --carry-frames N       PulseSearchOptions::carry_frames (default: the library's)
  --max-share X          RegistrationOptions::max_share (default: the library's)
  --affine-coarse        every registration's coarsest level an affine change
                         (RegistrationOptions::affine_coarse on)
  --no-affine-retry      no registration tried again with an affine coarsest level
                         (PulseSearchOptions::affine_retry off)
  --no-detail-retry      no registration tried again on the frames' detail
                         (PulseSearchOptions::detail_retry off)
  --detail-carry-frames N
                         PulseSearchOptions::detail_carry_frames (default: the library's)
  --no-field-alone       the field alone not looked for where the slope image fails
                         (PulseSearchOptions::field_alone off)
  --no-follow            a place carried not looked for where it is said to be before each search
                         (PulseSearchOptions::follow_carried off)
  --videos a,b           only these videos (screen kinds, or held-out contents; the tuning set's spreadsheet
                         only when named)
  --log FILE             one line per frame of the pulse search's videos: video, frame, state, where the
                         place came from, its error in modules, the share the pulse explained where searched,
                         ms, and the frame's registration onto the last: registered, residual, the residual
                         unmoved, overlap, whether aligned on the frames' detail, and (tuning set) how far the
                         registration put the frame's centre from the true motion's, pixels; then the place
                         carried: frames since it was found or confirmed, and the modules the aim has come over
                         the field since
  --seed N               scenario seed (default 1)
  --threads N            threads making frames (default: all cores)
  --help                 this text

Every video is also run without the field (the same frames, opacity 0): every place found there is wrong.
A place is right within half a module of the truth. Times are of one update on one thread: the tracker,
laying the frame onto the last and, where it ran, the search of the frames together.
Progress goes to stderr, the tables to stdout.
)";

struct Options {
    bool heldout = false;
    double min_opacity = 0.01, max_opacity = 0.04;
    int frames = 150;
    std::vector<cv::Size> resolutions{{640, 480}};
    bool announced = true;
    double frame_ms = 2;
    std::optional<double> max_motion_change;
    std::optional<double> max_follow_shape_change;
    double exposure_drift = 0;
    double readout_s = 0;
    int swing_speed = 1;
    std::optional<double> noise;
    std::optional<int> jpeg_quality;
    bool fit_gain = false;
    bool level_exposure = true;
    bool follow_carried = true;
    std::optional<int> carry_frames;
    bool affine_coarse = false;
    bool affine_retry = true;
    bool detail_retry = true;
    std::optional<int> detail_carry_frames;
    bool field_alone = true;
    std::optional<double> max_share;
    std::vector<std::string> videos;  // empty: all
    std::string log;
    std::uint64_t seed = 1;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
};

constexpr double kPeriodS = 1.5;
constexpr double kRadiusModules = 0.5;

// One video: its frames with the field and without, and where the field lies.
struct Video {
    std::string name;
    std::vector<Frame> field, bare;
    sim::FieldPlacement placement;
    double fps = 25;
    // The screen-to-image homography of each frame (the tuning set's; empty
    // for the held-out set): the true motion between frames.
    std::vector<cv::Matx33d> screen_to_image = {};
};

bool wanted(const Options& o, const std::string& video) {
    return o.videos.empty() || std::find(o.videos.begin(), o.videos.end(), video) != o.videos.end();
}

// The benchmark's pulse in place of the provider's default, which both
// sets' pulsing videos show (0.1 to 0.4, kHeldoutPulseMin and
// kHeldoutPulseMax): the same phase, scaled to the faint range.
double faint(const Options& o, double default_pulse_opacity) {
    return o.min_opacity + (o.max_opacity - o.min_opacity) * (default_pulse_opacity - kHeldoutPulseMin) /
                               (kHeldoutPulseMax - kHeldoutPulseMin);
}

std::vector<Video> tuning_videos(const Options& o, const Field& field, cv::Size res) {
    const Scene scene;
    const sim::FieldPlacement placement{{0, 0}, scene.module_px};
    std::vector<Video> out;
    // The spreadsheet's repeated cells only when named.
    for (const sim::ScreenKind kind : sim::kAllScreenKinds) {
        const bool everyday = std::find(sim::kEverydayScreenKinds.begin(), sim::kEverydayScreenKinds.end(), kind) !=
                              sim::kEverydayScreenKinds.end();
        if (o.videos.empty() ? !everyday : !wanted(o, sim::to_string(kind))) continue;
        const cv::Mat screen = sim::make_screen(kind, scene.screen.pixels, 7);
        // A faster swing: every K-th pose of a K times longer swing, at the
        // frames' own times (the pulse, the degradations and the exposure).
        auto rs = pulsing_recipes(scene, kind, o.frames * o.swing_speed, o.seed);
        for (int i = 0; i < o.frames; ++i) {
            rs[static_cast<std::size_t>(i)].pose = rs[static_cast<std::size_t>(i * o.swing_speed)].pose;
        }
        rs.resize(static_cast<std::size_t>(o.frames));
        for (FrameRecipe& r : rs) {
            r.degradation.exposure *= exposure_drift(r.index, o.exposure_drift, o.seed * 31 + static_cast<std::uint64_t>(kind));
            if (o.noise) r.degradation.noise_sigma = *o.noise;
            if (o.jpeg_quality) r.degradation.jpeg_quality = *o.jpeg_quality;
        }
        Video v{sim::to_string(kind), std::vector<Frame>(rs.size()), std::vector<Frame>(rs.size()), placement,
                sim::kFps};
        const sim::CameraModel camera{res, scene.hfov_deg};
        for (const FrameRecipe& r : rs) v.screen_to_image.push_back(sim::screen_to_image(scene.screen, camera, r.pose));
        parallel_for(static_cast<int>(rs.size()), o.threads, [&](int i) {
            const auto at = static_cast<std::size_t>(i);
            const double a = faint(o, pulsing_opacity(rs[at].index));
            v.field[at] = shoot(scene, rs[at], sim::mix_field(screen, field, placement, a), res);
            v.bare[at] = shoot(scene, rs[at], screen, res);
            if (o.readout_s > 0) {
                // The last frame moves on as from the one before it.
                const bool last = at + 1 == rs.size();
                const cv::Matx33d here = v.screen_to_image[at];
                const cv::Matx33d next = v.screen_to_image[last ? at - 1 : at + 1];
                const double readout = last ? -o.readout_s : o.readout_s;
                roll_shutter(v.field[at].grey, here, next, 1 / sim::kFps, readout);
                roll_shutter(v.bare[at].grey, here, next, 1 / sim::kFps, readout);
            }
        });
        out.push_back(std::move(v));
    }
    return out;
}

std::vector<Video> heldout_videos(const Options& o, const Field& field, cv::Size res) {
    std::vector<Video> out;
    const cv::Size modules(field.width, field.height);
    for (const sim::HeldoutContent content : sim::kAllHeldoutContents) {
        if (!wanted(o, sim::to_string(content))) continue;
        const auto rs = heldout_pulsing_recipes(content, o.frames, o.seed);
        const HeldoutScreen& s = heldout_screens()[static_cast<std::size_t>(rs.front().screen)];
        const sim::FieldPlacement placement = heldout_placement(s, field);
        const cv::Mat screen = sim::make_heldout_screen(content, s.geometry.pixels, kHeldoutScreenSeed);
        Video v{sim::to_string(content), std::vector<Frame>(rs.size()), std::vector<Frame>(rs.size()), placement,
                kHeldoutFps};
        parallel_for(static_cast<int>(rs.size()), o.threads, [&](int i) {
            const auto at = static_cast<std::size_t>(i);
            const double a = faint(o, heldout_pulsing_opacity(content, rs[at].index, o.seed));
            v.field[at] = shoot_heldout(rs[at], sim::mix_field(screen, field, placement, a), res, placement, modules);
            v.bare[at] = shoot_heldout(rs[at], screen, res, placement, modules);
            v.bare[at].centre_on_screen = v.field[at].centre_on_screen;
        });
        out.push_back(std::move(v));
    }
    return out;
}

PulseSearchOptions pulse_options(const Options& o, double fps) {
    PulseSearchOptions p;
    if (o.max_motion_change) p.max_motion_change = *o.max_motion_change;
    if (o.max_follow_shape_change) p.max_follow_shape_change = *o.max_follow_shape_change;
    p.registration.fit_gain = o.fit_gain;
    p.level_exposure = o.level_exposure;
    p.follow_carried = o.follow_carried;
    if (o.carry_frames) p.carry_frames = *o.carry_frames;
    p.registration.affine_coarse = o.affine_coarse;
    p.affine_retry = o.affine_retry;
    p.detail_retry = o.detail_retry;
    if (o.detail_carry_frames) p.detail_carry_frames = *o.detail_carry_frames;
    p.field_alone = o.field_alone;
    if (o.max_share) p.registration.max_share = *o.max_share;
    if (!o.announced) return p;
    p.shape = overlay::announced_pulse_shape(overlay::Waveform::sine, kPeriodS, o.min_opacity, o.max_opacity);
    p.frame_rates = {fps};
    return p;
}

// What one method made of one video's frames whose centre is on the field.
struct Tally {
    int evaluated = 0, right = 0, wrong = 0, demodulated = 0;
    int first_right = -1;  // frame index
    int longest_gap = 0;   // evaluated frames in a row without a right place, after the first
    int unregistered = 0;  // frames the pulse search could not lay onto the one before
    std::vector<double> ms;

    void add(int index, const Frame& f, const sim::FieldPlacement& placement, bool locked,
             const Eigen::Vector2d& aim_field, bool from_pulse, double update_ms) {
        ms.push_back(update_ms);
        if (!f.centre_on_screen) return;
        ++evaluated;
        bool ok = false;
        if (locked) {
            const cv::Point2d at = sim::field_to_screen(placement, {aim_field.x(), aim_field.y()});
            ok = cv::norm(at - f.centre_screen_px) / placement.module_px <= kRadiusModules;
            (ok ? right : wrong) += 1;
            demodulated += ok && from_pulse ? 1 : 0;
        }
        if (ok && first_right < 0) first_right = index;
        gap_ = ok ? 0 : gap_ + 1;
        if (first_right >= 0) longest_gap = std::max(longest_gap, gap_);
    }
    void merge(const Tally& t) {
        evaluated += t.evaluated, right += t.right, wrong += t.wrong, demodulated += t.demodulated;
        unregistered += t.unregistered;
        longest_gap = std::max(longest_gap, t.longest_gap);
        ms.insert(ms.end(), t.ms.begin(), t.ms.end());
    }

private:
    int gap_ = 0;
};

TrackerOptions tracking(const Options& o) {
    TrackerOptions t;
    t.spread_search = o.frame_ms > 0;
    t.frame_ms = o.frame_ms;
    return t;
}

Tally run_tracker(const Detector& detector, const Options& o, const Video& v, const std::vector<Frame>& frames) {
    Tally t;
    Tracker tracker(detector, tracking(o));
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const auto t0 = BenchClock::now();
        const TrackResult r = tracker.update(grey_view(frames[i]));
        const double ms = ms_between(t0, BenchClock::now());
        t.add(static_cast<int>(i), frames[i], v.placement, r.state == TrackState::locked, r.aim_field, false, ms);
    }
    return t;
}

// How far (pixels) `registered` puts the frame's centre, where a place is
// carried to, from where the true motion between the two frames' poses
// puts it.
double registration_error(const Eigen::Matrix3d& registered, const cv::Matx33d& from, const cv::Matx33d& to,
                          cv::Size size) {
    const cv::Vec3d t = to * from.inv() * cv::Vec3d((size.width - 1) / 2.0, (size.height - 1) / 2.0, 1);
    const Eigen::Vector3d r = registered * Eigen::Vector3d((size.width - 1) / 2.0, (size.height - 1) / 2.0, 1);
    return std::hypot(t[0] / t[2] - r.x() / r.z(), t[1] / t[2] - r.y() / r.z());
}

Tally run_pulse(const Detector& detector, const Options& o, const Video& v, const std::vector<Frame>& frames,
                std::ostream* log) {
    Tally t;
    PulseTracker tracker(detector, tracking(o), pulse_options(o, v.fps));
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const PulseTrackResult r = tracker.update(grey_view(frames[i]));
        t.add(static_cast<int>(i), frames[i], v.placement, r.track.state == TrackState::locked, r.track.aim_field,
              r.demodulated, r.ms);
        if (log) {
            *log << v.name << "\t" << i << "\t" << to_string(r.track.state) << "\t"
                 << (r.demodulated ? (r.track.used_prior ? "carried" : "demodulated") : "tracker") << "\t";
            if (r.track.state == TrackState::locked && frames[i].centre_on_screen)
                *log << cv::norm(sim::field_to_screen(v.placement, {r.track.aim_field.x(), r.track.aim_field.y()}) -
                                 frames[i].centre_screen_px) / v.placement.module_px;
            const FrameRegistration& g = tracker.pulse().last_registration();
            *log << "\t" << r.share << "\t" << r.ms << "\t" << g.registered << "\t" << g.residual << "\t"
                 << g.unmoved_residual << "\t" << g.overlap << "\t" << g.on_detail << "\t";
            if (i > 0 && !v.screen_to_image.empty())
                *log << registration_error(g.homography, v.screen_to_image[i - 1], v.screen_to_image[i], frames[i].grey.size());
            *log << "\t";
            const Eigen::Vector2d aim(frames[i].grey.cols / 2.0, frames[i].grey.rows / 2.0);
            if (const auto c = tracker.pulse().carry(aim)) *log << c->frames << "\t" << c->travel;
            *log << "\n";
        }
    }
    t.unregistered = tracker.pulse().registration_losses();
    return t;
}

std::string cell(const Tally& t) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%d / %d", t.right, t.wrong);
    return buf;
}

std::string ms_cell(const Tally& t) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f / %.2f", percentile(t.ms, 50), percentile(t.ms, 95));
    return buf;
}

void run(const Options& o) {
    const Field field = bench_field("b4-64x36.json");
    const Detector detector(field);
    std::optional<std::ofstream> log;
    if (!o.log.empty()) {
        log.emplace(o.log);
        if (!*log) throw std::runtime_error("cannot write " + o.log);
    }
    std::printf("Set %s, the field pulsing between opacity %.3g and %.3g (sine, %.1f s), %d frames a video, pulse %s, "
                "the tracker's search held to %.3g ms a frame (0: every search), seed %llu; right within %.1f module; ms of one "
                "update on one thread (median / p95).\n",
                o.heldout ? "held-out" : "tuning", o.min_opacity, o.max_opacity, kPeriodS, o.frames,
                o.announced ? "announced" : "not announced", o.frame_ms, static_cast<unsigned long long>(o.seed), kRadiusModules);
    if (o.exposure_drift > 0 && !o.heldout) std::printf("The exposure drifting by up to about %.3g.\n", o.exposure_drift);
    if (o.readout_s > 0 && !o.heldout) std::printf("A rolling shutter reading the rows over %.3g s.\n", o.readout_s);
    if (o.swing_speed > 1 && !o.heldout) std::printf("The hand swinging %d times as fast.\n", o.swing_speed);
    if (o.noise && !o.heldout) std::printf("Sensor noise of %.3g grey levels.\n", *o.noise);
    if (o.jpeg_quality && !o.heldout) std::printf("JPEG quality %d.\n", *o.jpeg_quality);
    if (o.fit_gain) std::printf("Registered with the exposure's gain as well as an offset.\n");
    if (!o.level_exposure) std::printf("Not levelled to one exposure before demodulating.\n");
    if (!o.follow_carried) std::printf("A place carried not followed before a search.\n");
    if (o.carry_frames) std::printf("A place carried at most %d frames.\n", *o.carry_frames);
    if (o.max_share) std::printf("Registered at up to %.3g of the unaligned residual.\n", *o.max_share);
    if (o.affine_coarse) std::printf("Every registration's coarsest level an affine change.\n");
    if (!o.affine_retry) std::printf("No registration tried again with an affine coarsest level.\n");
    if (!o.detail_retry) std::printf("No registration tried again on the frames' detail.\n");
    if (o.detail_carry_frames)
        std::printf("A place carried through at most %d registrations on the frames' detail.\n", *o.detail_carry_frames);
    if (!o.field_alone) std::printf("The field alone not looked for.\n");
    for (const cv::Size res : o.resolutions) {
        std::cerr << "making " << res.width << " x " << res.height << " videos\n";
        const std::vector<Video> videos = o.heldout ? heldout_videos(o, field, res) : tuning_videos(o, field, res);
        std::printf("\n### %d x %d\n\n", res.width, res.height);
        std::printf("| video | frames | tracker right / wrong | with the pulse search right / wrong | of them "
                    "demodulated | first right | longest gap | not registered | ms | without the field: found (wrong) | ms |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
        Tally all_tracker, all_pulse, all_bare;
        for (const Video& v : videos) {
            std::cerr << "  " << v.name << "\n";
            const Tally tracker = run_tracker(detector, o, v, v.field);
            const Tally pulse = run_pulse(detector, o, v, v.field, log ? &*log : nullptr);
            const Tally bare = run_pulse(detector, o, v, v.bare, nullptr);
            std::printf("| %s | %d | %s | %s | %d | %d | %d | %d | %s | %d | %s |\n", v.name.c_str(), pulse.evaluated,
                        cell(tracker).c_str(), cell(pulse).c_str(), pulse.demodulated, pulse.first_right,
                        pulse.longest_gap, pulse.unregistered, ms_cell(pulse).c_str(), bare.right + bare.wrong,
                        ms_cell(bare).c_str());
            std::fflush(stdout);
            all_tracker.merge(tracker);
            all_pulse.merge(pulse);
            all_bare.merge(bare);
        }
        std::printf("| **all** | %d | %s | **%s** | %d | | %d | %d | %s | %d | %s |\n", all_pulse.evaluated,
                    cell(all_tracker).c_str(), cell(all_pulse).c_str(), all_pulse.demodulated, all_pulse.longest_gap,
                    all_pulse.unregistered, ms_cell(all_pulse).c_str(), all_bare.right + all_bare.wrong,
                    ms_cell(all_bare).c_str());
    }
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            return argv[++i];
        };
        if (a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "--set") {
            const std::string s = value();
            if (s != "tuning" && s != "heldout") throw std::invalid_argument("--set: tuning or heldout, not " + s);
            o.heldout = s == "heldout";
        } else if (a == "--opacities") {
            if (std::sscanf(value().c_str(), "%lf,%lf", &o.min_opacity, &o.max_opacity) != 2 || !(o.min_opacity >= 0) ||
                !(o.max_opacity > o.min_opacity) || o.max_opacity > 1)
                throw std::invalid_argument("--opacities: MIN,MAX with 0 <= MIN < MAX <= 1");
        } else if (a == "--frames") {
            o.frames = std::stoi(value());
            if (o.frames < 1) throw std::invalid_argument("--frames: at least 1");
        } else if (a == "--resolutions") {
            o.resolutions = parse_resolutions(value());
        } else if (a == "--frame-ms") {
            o.frame_ms = std::stod(value());
            if (!(o.frame_ms >= 0)) throw std::invalid_argument("--frame-ms: 0 or more");
        } else if (a == "--not-announced") {
            o.announced = false;
        } else if (a == "--max-motion-change") {
            o.max_motion_change = std::stod(value());
        } else if (a == "--max-follow-shape-change") {
            o.max_follow_shape_change = std::stod(value());
        } else if (a == "--exposure-drift") {
            o.exposure_drift = std::stod(value());
            if (!(o.exposure_drift >= 0 && o.exposure_drift < 0.5)) throw std::invalid_argument("--exposure-drift: 0 to 0.5");
        } else if (a == "--rolling-shutter") {
            o.readout_s = std::stod(value());
            if (!(o.readout_s >= 0 && o.readout_s < 1 / sim::kFps))
                throw std::invalid_argument("--rolling-shutter: 0 to one frame's interval (0.04 s)");
        } else if (a == "--swing-speed") {
            o.swing_speed = std::stoi(value());
            if (o.swing_speed < 1 || o.swing_speed > 8) throw std::invalid_argument("--swing-speed: 1 to 8");
        } else if (a == "--noise") {
            o.noise = std::stod(value());
            if (!(*o.noise >= 0 && *o.noise <= 30)) throw std::invalid_argument("--noise: 0 to 30 grey levels");
        } else if (a == "--jpeg-quality") {
            o.jpeg_quality = std::stoi(value());
            if (*o.jpeg_quality < 1 || *o.jpeg_quality > 100) throw std::invalid_argument("--jpeg-quality: 1 to 100");
        } else if (a == "--gain") {
            o.fit_gain = true;
        } else if (a == "--carry-frames") {
            o.carry_frames = std::stoi(value());
            if (*o.carry_frames < 0) throw std::invalid_argument("--carry-frames: 0 or more");
        } else if (a == "--max-share") {
            o.max_share = std::stod(value());
        } else if (a == "--affine-coarse") {
            o.affine_coarse = true;
        } else if (a == "--no-affine-retry") {
            o.affine_retry = false;
        } else if (a == "--no-detail-retry") {
            o.detail_retry = false;
        } else if (a == "--detail-carry-frames") {
            o.detail_carry_frames = std::stoi(value());
            if (*o.detail_carry_frames < 0) throw std::invalid_argument("--detail-carry-frames: 0 or more");
        } else if (a == "--no-field-alone") {
            o.field_alone = false;
        } else if (a == "--no-follow") {
            o.follow_carried = false;
        } else if (a == "--no-levelling") {
            o.level_exposure = false;
        } else if (a == "--videos") {
            std::stringstream list(value());
            for (std::string name; std::getline(list, name, ',');) o.videos.push_back(name);
        } else if (a == "--log") {
            o.log = value();
        } else if (a == "--seed") {
            o.seed = std::stoull(value());
        } else if (a == "--threads") {
            o.threads = std::max(1, std::stoi(value()));
        } else {
            throw std::invalid_argument("unknown option " + a + " (--help lists them)");
        }
    }
    return o;
}

}  // namespace
}  // namespace umf::bench

int main(int argc, char** argv) {
    try {
        umf::bench::run(umf::bench::parse(argc, argv));
    } catch (const std::exception& e) {
        std::cerr << "umf_pulse_benchmark: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
