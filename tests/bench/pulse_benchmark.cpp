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
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include <Eigen/Dense>

#include "shared/detect/field_shift.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/bench/heldout_run.hpp"
#include "tests/bench/heldout_scenario.hpp"
#include "tests/bench/methods.hpp"
#include "tests/bench/phone_effects.hpp"
#include "tests/bench/pulse_benchmark_options.hpp"
#include "tests/bench/scenario.hpp"
#include "tests/sim/field_mix.hpp"
#include "tests/sim/phone_processing.hpp"
#include "tests/sim/sequence.hpp"

namespace umf::bench {
namespace {

// A grey frame through a phone's local tone mapping (sim::local_tone_map).
cv::Mat locally_tone_mapped(const cv::Mat& grey, double strength) {
    cv::Mat bgr, out;
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    cv::cvtColor(sim::local_tone_map(bgr, strength), out, cv::COLOR_BGR2GRAY);
    return out;
}

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

bool wanted(const PulseBenchmarkOptions& o, const std::string& video) {
    return o.videos.empty() || std::find(o.videos.begin(), o.videos.end(), video) != o.videos.end();
}

// The benchmark's pulse in place of the provider's default, which both
// sets' pulsing videos show (0.1 to 0.4, kHeldoutPulseMin and
// kHeldoutPulseMax): the same phase, scaled to the faint range.
double faint(const PulseBenchmarkOptions& o, double default_pulse_opacity) {
    return o.min_opacity + (o.max_opacity - o.min_opacity) * (default_pulse_opacity - kHeldoutPulseMin) /
                               (kHeldoutPulseMax - kHeldoutPulseMin);
}

std::vector<Video> tuning_videos(const PulseBenchmarkOptions& o, const Field& field, cv::Size res) {
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
            if (o.optics != PulseBenchmarkOptions::Optics::drawn) {
                // No smear, stripes or lamp on any frame; the defocus each
                // frame's own (plain), or the same 1 pixel on every frame
                // (steady): whether what changes from frame to frame in
                // the camera, not the pulse, is what the pulse search loses.
                r.degradation.motion_blur_px = 0;
                r.degradation.subpixels = false;
                r.degradation.glare = 0;
                if (o.optics == PulseBenchmarkOptions::Optics::steady) r.degradation.defocus_sigma_px = 1.0;
            }
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
            if (o.local_tone > 0)
                for (Frame* f : {&v.field[at], &v.bare[at]}) f->grey = locally_tone_mapped(f->grey, o.local_tone);
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

std::vector<Video> heldout_videos(const PulseBenchmarkOptions& o, const Field& field, cv::Size res) {
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

PulseSearchOptions pulse_options(const PulseBenchmarkOptions& o, double fps) {
    PulseSearchOptions p;
    if (o.max_motion_change) p.max_motion_change = *o.max_motion_change;
    if (o.max_follow_shape_change) p.max_follow_shape_change = *o.max_follow_shape_change;
    p.registration.fit_gain = o.fit_gain;
    p.level_exposure = o.level_exposure;
    p.follow_carried = o.follow_carried;
    p.check_newest = o.check_newest;
    if (o.carry_frames) p.carry_frames = *o.carry_frames;
    p.registration.affine_coarse = o.affine_coarse;
    p.affine_retry = o.affine_retry;
    p.detail_retry = o.detail_retry;
    if (o.detail_carry_modules) p.detail_carry_modules = *o.detail_carry_modules;
    p.field_alone = o.field_alone;
    if (!o.content_free) p.content_free_tile = 0;
    if (o.kept_frames) p.frames = *o.kept_frames;
    if (o.demodulation_level) p.demodulation_level = *o.demodulation_level;
    if (o.max_share) p.registration.max_share = *o.max_share;
    if (o.out_of_step_share) p.out_of_step_share = *o.out_of_step_share;
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

TrackerOptions tracking(const PulseBenchmarkOptions& o) {
    TrackerOptions t;
    t.spread_search = o.frame_ms > 0;
    t.frame_ms = o.frame_ms;
    return t;
}

Tally run_tracker(const Detector& detector, const PulseBenchmarkOptions& o, const Video& v, const std::vector<Frame>& frames) {
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

// A pulse place checked in its frame alone (field_shift.hpp), as the log
// writes it: the shift the frame's own field shows (pixels), its evidence
// there, at the place and from the content alone, the module's size
// (pixels), and the place's true error at the aim (pixels,
// through the map's local derivative), which the shift should match.
void log_field_shift(std::ostream& log, const Detector& detector, const Frame& frame, const Detection& place,
                     const sim::FieldPlacement& placement, const Eigen::Vector2d& aim) {
    const FieldShift fs = field_shift(grey_view(frame), detector.field(), place.image_to_field);
    const std::optional<Eigen::Matrix2d> d = homography_derivative(place.image_to_field, aim);
    const std::optional<Point2> at = apply_homography(place.image_to_field, aim);
    if (!d || !at || std::abs(d->determinant()) < 1e-12) return;
    // The frame's centre in the simulator's pixels is half a pixel on from the detector's aim.
    const cv::Point2d truth = sim::screen_to_field(placement, frame.centre_screen_px);
    const Eigen::Vector2d off = d->inverse() * (*at - Eigen::Vector2d(truth.x, truth.y)) - Eigen::Vector2d(0.5, 0.5);
    log << fs.shift.x() << "\t" << fs.shift.y() << "\t" << fs.best_t << "\t" << fs.place_t << "\t" << fs.content_t
        << "\t" << fs.module_px << "\t" << off.x() << "\t" << off.y();
}

Tally run_pulse(const Detector& detector, const PulseBenchmarkOptions& o, const Video& v, const std::vector<Frame>& frames,
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
                 << g.unmoved_residual << "\t" << g.overlap << "\t" << g.on_detail << "\t" << g.guess_residual
                 << "\t";
            const std::size_t span = static_cast<std::size_t>(tracker.pulse().last_registration_span());
            if (i >= span && !v.screen_to_image.empty())
                *log << registration_error(g.homography, v.screen_to_image[i - span], v.screen_to_image[i],
                                           frames[i].grey.size());
            *log << "\t";
            const Eigen::Vector2d aim(frames[i].grey.cols / 2.0, frames[i].grey.rows / 2.0);
            if (const auto c = tracker.pulse().carry(aim)) *log << c->frames << "\t" << c->travel;
            *log << "\t";
            if (r.track.state == TrackState::locked && r.demodulated && frames[i].centre_on_screen)
                log_field_shift(*log, detector, frames[i], r.track.detection, v.placement, aim);
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

void run(const PulseBenchmarkOptions& o) {
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
    if (o.local_tone > 0 && !o.heldout) std::printf("Local tone mapping of strength %.3g.\n", o.local_tone);
    if (o.fit_gain) std::printf("Registered with the exposure's gain as well as an offset.\n");
    if (!o.level_exposure) std::printf("Not levelled to one exposure before demodulating.\n");
    if (o.optics == PulseBenchmarkOptions::Optics::steady && !o.heldout)
        std::printf("Steady optics: no smear, stripes or lamp, every frame defocused by 1 px.\n");
    else if (o.optics == PulseBenchmarkOptions::Optics::plain && !o.heldout)
        std::printf("Plain optics: no smear, stripes or lamp, each frame's own defocus.\n");
    if (!o.follow_carried) std::printf("A place carried not followed before a search.\n");
    if (o.carry_frames) std::printf("A place carried at most %d frames.\n", *o.carry_frames);
    if (o.max_share) std::printf("Registered at up to %.3g of the unaligned residual.\n", *o.max_share);
    if (o.affine_coarse) std::printf("Every registration's coarsest level an affine change.\n");
    if (!o.affine_retry) std::printf("No registration tried again with an affine coarsest level.\n");
    if (!o.detail_retry) std::printf("No registration tried again on the frames' detail.\n");
    if (o.detail_carry_modules)
        std::printf("A place carried through registrations on the frames' detail while the view has come at most %g modules.\n",
                    *o.detail_carry_modules);
    if (!o.field_alone) std::printf("The field alone not looked for.\n");
    if (!o.content_free) std::printf("The slope without the content's leakage not looked in.\n");
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

}  // namespace
}  // namespace umf::bench

int main(int argc, char** argv) {
    try {
        umf::bench::run(umf::bench::parse_pulse_options(argc, argv));
    } catch (const std::exception& e) {
        std::cerr << "umf_pulse_benchmark: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
