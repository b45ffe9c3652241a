#include "tests/bench/heldout_scenario.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "tests/sim/sequence.hpp"

namespace umf::bench {
namespace {

constexpr int kClipFrames = 10;
constexpr double kTwoPi = 2 * CV_PI;
// Mixed into every held-out seed, so that no stream coincides with one of
// the tuning set's for the same --seed.
constexpr std::uint64_t kHeldoutSalt = 0x48454C444F555431ull;

std::uint64_t mix(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
    std::uint64_t z = seed ^ kHeldoutSalt;
    z += 0x9E3779B97F4A7C15ull * (a + 1) + 0xD6E8FEB86659FD93ull * (b + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return z == 0 ? 1 : z;
}

// What a category asks of its clips: how large a module appears at the
// reference width (image px), how far the camera tilts, how fast it moves.
struct Spec {
    double module_lo, module_hi;     // image px per module at 1280 px width
    double tilt_lo, tilt_hi;         // degrees
    double roll_rate;                // max |deg/s| of the roll's drift
    double aim_speed;                // max screen widths per second along the path
};

Spec spec_of(HeldoutCategory c) {
    switch (c) {
    case HeldoutCategory::rotation: return {12, 25, 0, 20, 120, 0.1};
    case HeldoutCategory::perspective: return {12, 25, 35, 60, 30, 0.1};
    case HeldoutCategory::near: return {35, 80, 0, 30, 30, 0.08};
    case HeldoutCategory::far: return {6, 9, 0, 25, 30, 0.1};
    case HeldoutCategory::motion: return {12, 25, 0, 30, 90, 0.5};
    case HeldoutCategory::moire: return {0, 0, 0, 25, 30, 0.1};  // sized by the screen pixel instead
    case HeldoutCategory::general:
    case HeldoutCategory::low_light:
    case HeldoutCategory::occlusion: return {10, 30, 0, 40, 45, 0.15};
    }
    return {10, 30, 0, 40, 45, 0.15};
}

double focal_at_reference(double hfov_deg) { return kReferenceWidth / 2 / std::tan(hfov_deg * CV_PI / 360); }

// The phone's everyday processing and degradations of one frame. Every draw
// happens unconditionally so the stream does not depend on what came out on.
sim::PhoneShot everyday(cv::RNG& rng, const HeldoutScreen& screen, double t_s, std::uint64_t seed) {
    sim::PhoneShot s;
    s.bezel_mm = rng.uniform(4.0, 9.0);
    s.readout_s = rng.uniform(0.015, 0.03);
    s.defocus_sigma_px = rng.uniform(0.4, 1.2);
    const bool smeared = rng.uniform(0.0, 1.0) < 0.3;
    const sim::CurvedBlur smear{rng.uniform(1.0, 3.0), rng.uniform(0.0, 360.0), rng.uniform(-120.0, 120.0)};
    if (smeared) s.blur = smear;
    const bool structured = rng.uniform(0.0, 1.0) < 0.2;
    if (structured) s.structure = sim::PixelStructure{screen.layout, screen.fill, 4};
    const bool lamp = rng.uniform(0.0, 1.0) < 0.1;
    const double glare = rng.uniform(0.1, 0.3);
    if (lamp) s.glare = glare;
    s.metering_target = rng.uniform(0.22, 0.4);
    s.hunt = sim::exposure_hunt(t_s, seed);
    s.read_noise = rng.uniform(1.5, 3.0);
    s.shot_noise = rng.uniform(2.0, 5.0);
    const bool denoised = rng.uniform(0.0, 1.0) < 0.5;
    const double denoise = rng.uniform(4.0, 12.0);
    if (denoised) s.processing.denoise = denoise;
    s.processing.sharpen_amount = rng.uniform(0.3, 1.2);
    s.processing.sharpen_sigma_px = rng.uniform(1.0, 2.0);
    s.processing.local_tone = rng.uniform(0.0, 0.5);
    s.compression.quality = rng.uniform(35, 61);
    s.compression.flat_threshold = rng.uniform(1.0, 2.5);
    s.seed = mix(seed, 77);
    return s;
}

// One clip's smooth curved path: the aim point circles along an arc, the
// module size (distance) drifts, the tilt and roll drift.
struct Clip {
    int screen;
    sim::HeldoutContent content;
    double hfov;
    double module0, module1;  // image px per module at the start and end (reference width)
    cv::Point2d aim0;         // screen px
    double radius_px, omega, phase;
    double tilt, tilt_dir, tilt_rate;
    double roll0, roll_rate;
};

Clip make_clip(cv::RNG& rng, HeldoutCategory category, int clip, const Spec& spec) {
    Clip c;
    c.screen = (clip + static_cast<int>(category)) % 3;
    c.content = sim::kAllHeldoutContents[static_cast<std::size_t>((2 * clip + static_cast<int>(category)) % 5)];
    c.hfov = rng.uniform(70.0, 80.0);
    const HeldoutScreen& s = heldout_screens()[static_cast<std::size_t>(c.screen)];
    double lo = spec.module_lo, hi = spec.module_hi;
    if (category == HeldoutCategory::moire) {
        // Screen pixels of 0.6..1.6 image px: where the sensor aliases most.
        const double module_px = s.geometry.pixels.width / 64.0;
        lo = 0.6 * module_px;
        hi = 1.6 * module_px;
    }
    c.module0 = rng.uniform(lo, hi);
    c.module1 = rng.uniform(lo, hi);
    const cv::Size px = s.geometry.pixels;
    c.aim0 = {px.width * rng.uniform(0.2, 0.8), px.height * rng.uniform(0.25, 0.75)};
    const double speed = rng.uniform(0.3, 1.0) * spec.aim_speed * px.width;  // screen px per second
    c.omega = rng.uniform(1.5, 4.0) * (rng.uniform(0, 2) ? 1 : -1);         // the path's turning, rad/s
    c.radius_px = speed / std::abs(c.omega);
    c.phase = rng.uniform(0.0, kTwoPi);
    c.tilt = rng.uniform(spec.tilt_lo, spec.tilt_hi);
    c.tilt_dir = rng.uniform(0.0, kTwoPi);
    c.tilt_rate = rng.uniform(-0.6, 0.6);
    c.roll0 = rng.uniform(-180.0, 180.0);
    c.roll_rate = rng.uniform(-1.0, 1.0) * spec.roll_rate;
    if (category == HeldoutCategory::rotation) c.roll_rate = (rng.uniform(0, 2) ? 1 : -1) * rng.uniform(0.5, 1.0) * spec.roll_rate;
    return c;
}

sim::CameraPose clip_pose(const Clip& c, double t) {
    const HeldoutScreen& s = heldout_screens()[static_cast<std::size_t>(c.screen)];
    const double module_mm = s.geometry.width_mm / 64.0;
    const double clip_s = kClipFrames / kHeldoutFps;
    const double m = c.module0 + (c.module1 - c.module0) * std::min(1.0, t / clip_s);
    sim::CameraPose p;
    p.distance_mm = focal_at_reference(c.hfov) * module_mm / m;
    const double a = c.phase + c.omega * t;
    p.aim_screen_px = c.aim0 + c.radius_px * cv::Point2d(std::cos(a) - std::cos(c.phase), std::sin(a) - std::sin(c.phase));
    const double dir = c.tilt_dir + c.tilt_rate * t;
    p.pitch_deg = c.tilt * std::cos(dir) + 0.5 * std::sin(11 * t + c.phase);
    p.yaw_deg = c.tilt * std::sin(dir) + 0.5 * std::cos(9 * t + c.phase);
    p.roll_deg = c.roll0 + c.roll_rate * t;
    return p;
}

// The pose's rate of change at t, for the rolling shutter and the smear.
template <class PoseAt>
sim::PoseVelocity velocity_of(const PoseAt& pose_at, double t) {
    constexpr double dt = 1e-3;
    const sim::CameraPose a = pose_at(t - dt), b = pose_at(t + dt);
    sim::PoseVelocity v;
    v.distance_mm = (b.distance_mm - a.distance_mm) / (2 * dt);
    v.pitch_deg = (b.pitch_deg - a.pitch_deg) / (2 * dt);
    v.yaw_deg = (b.yaw_deg - a.yaw_deg) / (2 * dt);
    v.roll_deg = (b.roll_deg - a.roll_deg) / (2 * dt);
    v.aim_screen_px = (b.aim_screen_px - a.aim_screen_px) / (2 * dt);
    return v;
}

// The pulsing video's long path: every quantity a slow swing of its own
// period and phase, plus a hand's tremor.
struct Walk {
    int screen;
    double hfov;
    double log_module_mid, log_module_amp, module_period, module_phase;
    double tilt_period, tilt_phase, tilt_dir0, tilt_dir_rate;
    double roll0, roll_amp, roll_period, roll_phase;
    double aim_period, aim_phase_x, aim_phase_y;
    double tremor_hz, tremor_phase;
};

Walk make_walk(cv::RNG& rng, int screen, const Spec& spec) {
    Walk w;
    w.screen = screen;
    w.hfov = rng.uniform(70.0, 80.0);
    w.log_module_mid = (std::log(spec.module_lo) + std::log(spec.module_hi)) / 2;
    w.log_module_amp = (std::log(spec.module_hi) - std::log(spec.module_lo)) / 2;
    w.module_period = rng.uniform(4.0, 6.0);
    w.module_phase = rng.uniform(0.0, kTwoPi);
    w.tilt_period = rng.uniform(5.0, 7.0);
    w.tilt_phase = rng.uniform(0.0, kTwoPi);
    w.tilt_dir0 = rng.uniform(0.0, kTwoPi);
    w.tilt_dir_rate = rng.uniform(-0.5, 0.5);
    w.roll0 = rng.uniform(-180.0, 180.0);
    w.roll_amp = rng.uniform(10.0, 30.0);
    w.roll_period = rng.uniform(6.0, 9.0);
    w.roll_phase = rng.uniform(0.0, kTwoPi);
    w.aim_period = rng.uniform(7.0, 10.0);
    w.aim_phase_x = rng.uniform(0.0, kTwoPi);
    w.aim_phase_y = rng.uniform(0.0, kTwoPi);
    w.tremor_hz = rng.uniform(1.5, 3.0);
    w.tremor_phase = rng.uniform(0.0, kTwoPi);
    return w;
}

sim::CameraPose walk_pose(const Walk& w, const Spec& spec, double t) {
    const HeldoutScreen& s = heldout_screens()[static_cast<std::size_t>(w.screen)];
    const double module_mm = s.geometry.width_mm / 64.0;
    const double tremor = std::sin(kTwoPi * w.tremor_hz * t + w.tremor_phase);
    const double m = std::exp(w.log_module_mid + w.log_module_amp * std::sin(kTwoPi * t / w.module_period + w.module_phase));
    sim::CameraPose p;
    p.distance_mm = focal_at_reference(w.hfov) * module_mm / m + 2 * tremor;
    const double tilt = spec.tilt_hi / 2 * (1 - std::cos(kTwoPi * t / w.tilt_period + w.tilt_phase));
    const double dir = w.tilt_dir0 + w.tilt_dir_rate * t;
    p.pitch_deg = tilt * std::cos(dir) + 0.6 * tremor;
    p.yaw_deg = tilt * std::sin(dir) + 0.4 * tremor;
    p.roll_deg = w.roll0 + w.roll_amp * std::sin(kTwoPi * t / w.roll_period + w.roll_phase) + 0.8 * tremor;
    const cv::Size px = s.geometry.pixels;
    p.aim_screen_px = {px.width * (0.5 + 0.3 * std::sin(kTwoPi * t / w.aim_period + w.aim_phase_x)),
                       px.height * (0.5 + 0.2 * std::sin(kTwoPi * t / (1.3 * w.aim_period) + w.aim_phase_y))};
    return p;
}

// Pulsing videos draw from streams of their own, apart from the categories'.
constexpr std::uint64_t kPulseStream = 100;

}  // namespace

const char* to_string(HeldoutCategory category) {
    switch (category) {
    case HeldoutCategory::general: return "general";
    case HeldoutCategory::rotation: return "rotation";
    case HeldoutCategory::perspective: return "perspective";
    case HeldoutCategory::near: return "near";
    case HeldoutCategory::far: return "far";
    case HeldoutCategory::motion: return "motion";
    case HeldoutCategory::low_light: return "low_light";
    case HeldoutCategory::occlusion: return "occlusion";
    case HeldoutCategory::moire: return "moire";
    }
    return "?";
}

std::optional<HeldoutCategory> heldout_category_from_string(const std::string& name) {
    for (HeldoutCategory c : kAllHeldoutCategories)
        if (name == to_string(c)) return c;
    return std::nullopt;
}

const std::array<HeldoutScreen, 3>& heldout_screens() {
    static const std::array<HeldoutScreen, 3> screens = {{
        {"laptop_13in_2560x1600", {{2560, 1600}, 286.5}, sim::PixelLayout::pentile, 0.6},
        {"monitor_27in_2560x1440", {{2560, 1440}, 596.7}, sim::PixelLayout::rgb_stripe, 0.8},
        {"laptop_15.6in_1920x1080", {{1920, 1080}, 344.2}, sim::PixelLayout::rgb_stripe, 0.7},
    }};
    return screens;
}

sim::FieldPlacement heldout_placement(const HeldoutScreen& screen, const Field& field) {
    const double module = static_cast<double>(screen.geometry.pixels.width) / field.width;
    return {{0, (screen.geometry.pixels.height - module * field.height) / 2}, module};
}

std::vector<HeldoutRecipe> heldout_recipes(HeldoutCategory category, int frames, std::uint64_t seed) {
    const auto cat = static_cast<std::uint64_t>(category);
    const Spec spec = spec_of(category);
    std::vector<HeldoutRecipe> out;
    Clip clip{};
    for (int i = 0; i < frames; ++i) {
        const int clip_index = i / kClipFrames;
        if (i % kClipFrames == 0) {
            cv::RNG clip_rng(mix(seed, cat, static_cast<std::uint64_t>(clip_index) + 1000));
            clip = make_clip(clip_rng, category, clip_index, spec);
        }
        const double t = (i % kClipFrames) / kHeldoutFps;
        cv::RNG rng(mix(seed, cat, static_cast<std::uint64_t>(i)));
        HeldoutRecipe r;
        r.index = i;
        r.screen = clip.screen;
        r.content = clip.content;
        r.hfov_deg = clip.hfov;
        r.pose = clip_pose(clip, t);
        const HeldoutScreen& screen = heldout_screens()[static_cast<std::size_t>(clip.screen)];
        r.shot = everyday(rng, screen, i / kHeldoutFps, mix(seed, cat, 5));
        r.shot.velocity = velocity_of([&](double at) { return clip_pose(clip, at); }, t);
        // Category-specific draws come after the everyday ones.
        const sim::CurvedBlur fast{rng.uniform(4.0, 14.0), rng.uniform(0.0, 360.0),
                                   rng.uniform(30.0, 180.0) * (rng.uniform(0, 2) ? 1 : -1)};
        const double dark = rng.uniform(0.35, 0.6), read = rng.uniform(5.0, 9.0), shot = rng.uniform(8.0, 14.0);
        const double strong_denoise = rng.uniform(15.0, 25.0);
        const int moire_samples = rng.uniform(2, 4);  // 2 x 2 or 3 x 3 over the sensor pixel's area
        const bool near_structure = rng.uniform(0.0, 1.0) < 0.6;
        const std::uint64_t occluder = mix(seed, cat, static_cast<std::uint64_t>(i) + 5000);
        switch (category) {
        case HeldoutCategory::motion: r.shot.blur = fast; break;
        case HeldoutCategory::low_light:
            r.shot.exposure_scale = dark;
            r.shot.read_noise = read;
            r.shot.shot_noise = shot;
            r.shot.processing.denoise = strong_denoise;
            break;
        case HeldoutCategory::moire: r.shot.structure = sim::PixelStructure{screen.layout, screen.fill, moire_samples}; break;
        case HeldoutCategory::near:
            if (near_structure) r.shot.structure = sim::PixelStructure{screen.layout, screen.fill, 3};
            break;
        case HeldoutCategory::occlusion: r.occluder_seed = occluder; break;
        default: break;
        }
        out.push_back(r);
    }
    return out;
}

std::vector<HeldoutRecipe> heldout_pulsing_recipes(sim::HeldoutContent content, int frames, std::uint64_t seed) {
    const auto stream = kPulseStream + static_cast<std::uint64_t>(content);
    const Spec spec = spec_of(HeldoutCategory::general);
    cv::RNG walk_rng(mix(seed, stream, 1000));
    const Walk walk = make_walk(walk_rng, static_cast<int>(content) % 3, spec);
    const auto pose_at = [&](double t) { return walk_pose(walk, spec, t); };
    const HeldoutScreen& screen = heldout_screens()[static_cast<std::size_t>(walk.screen)];
    std::vector<HeldoutRecipe> out;
    for (int i = 0; i < frames; ++i) {
        const double t = i / kHeldoutFps;
        cv::RNG rng(mix(seed, stream, static_cast<std::uint64_t>(i)));
        HeldoutRecipe r;
        r.index = i;
        r.screen = walk.screen;
        r.content = content;
        r.hfov_deg = walk.hfov;
        r.pose = pose_at(t);
        r.shot = everyday(rng, screen, t, mix(seed, stream, 5));
        r.shot.velocity = velocity_of(pose_at, t);
        out.push_back(r);
    }
    return out;
}

double heldout_pulsing_opacity(sim::HeldoutContent content, int frame, std::uint64_t seed) {
    cv::RNG rng(mix(seed, kPulseStream + static_cast<std::uint64_t>(content), 2000));
    const double phase_s = rng.uniform(0.0, kHeldoutPulsePeriodS);
    return sim::pulse_opacity(phase_s + frame / kHeldoutFps, kHeldoutPulseMin, kHeldoutPulseMax,
                              kHeldoutPulsePeriodS);
}

Frame shoot_heldout(const HeldoutRecipe& r, const cv::Mat& mixed, cv::Size resolution, const sim::FieldPlacement& placement,
                    cv::Size field_modules) {
    const HeldoutScreen& screen = heldout_screens()[static_cast<std::size_t>(r.screen)];
    const double k = resolution.width / kReferenceWidth;
    sim::PhoneShot s = r.shot;
    s.defocus_sigma_px *= k;
    s.blur.length_px *= k;
    s.processing.sharpen_sigma_px *= k;
    const sim::CameraModel camera{resolution, r.hfov_deg};
    sim::Shot shot = sim::photograph_phone(mixed, screen.geometry, camera, r.pose, s, placement.module_px);
    Frame f;
    f.centre_screen_px = shot.centre_screen_px;
    const cv::Point2d uv = sim::screen_to_field(placement, shot.centre_screen_px);
    f.centre_on_screen = shot.centre_on_screen && uv.x >= 0 && uv.y >= 0 && uv.x < field_modules.width &&
                         uv.y < field_modules.height;
    f.module_px_in_image = shot.module_px_in_image;
    if (r.occluder_seed) {
        f.occluded_fraction = draw_occluder(shot.bgr, *r.occluder_seed, s.defocus_sigma_px, s.read_noise);
        cv::cvtColor(shot.bgr, f.grey, cv::COLOR_BGR2GRAY);
    } else {
        f.grey = shot.grey;
    }
    return f;
}

}  // namespace umf::bench
