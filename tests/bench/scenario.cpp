#include "tests/bench/scenario.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace umf::bench {
namespace {

constexpr double kTwoPi = 2 * CV_PI;

// Seeds for independent streams (frame k's noise, frame k's occluder, ...)
// from one base seed: splitmix64, so neighbouring inputs give unrelated
// outputs and cv::RNG never sees a zero state.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (a + 1) + 0xBF58476D1CE4E5B9ull * (b + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return z == 0 ? 1 : z;
}

// What every frame goes through on the way to the phone's JPEG: some defocus
// (autofocus hunting), sensor noise, JPEG at a phone's default quality, and
// now and then motion smear, the screen's RGB stripes (moire) and a lamp's
// reflection. Every draw happens unconditionally, so the stream, and with it
// every later frame, does not depend on which effects came out on.
sim::Degradation everyday_degradation(std::uint64_t seed, int frame) {
    cv::RNG rng(mix_seed(seed, static_cast<std::uint64_t>(frame), 1));
    sim::Degradation d;
    d.defocus_sigma_px = rng.uniform(0.5, 1.5);
    d.noise_sigma = rng.uniform(2.0, 3.0);
    d.jpeg_quality = 80;
    const bool smeared = rng.uniform(0.0, 1.0) < 0.3;
    const double smear_px = rng.uniform(1.0, 4.0);
    const double smear_deg = rng.uniform(0.0, 180.0);
    if (smeared) {
        d.motion_blur_px = smear_px;
        d.motion_angle_deg = smear_deg;
    }
    d.subpixels = rng.uniform(0.0, 1.0) < 0.15;
    const bool lamp = rng.uniform(0.0, 1.0) < 0.1;
    const double glare = rng.uniform(0.1, 0.25);
    if (lamp) d.glare = glare;
    d.seed = mix_seed(seed, static_cast<std::uint64_t>(frame), 2);
    return d;
}

sim::Motion motion_of(Category category) {
    switch (category) {
    case Category::near_far: return sim::Motion::near_far;
    case Category::horizontal: return sim::Motion::horizontal;
    case Category::rotation: return sim::Motion::rotation;
    case Category::perspective: return sim::Motion::perspective;
    case Category::distant:
    case Category::tiny: return sim::Motion::near_far;
    case Category::general:
    case Category::occlusion:
    case Category::low_light:
    case Category::smeared:
    case Category::compressed:
    case Category::pixel_grid:
    case Category::ruled:
    case Category::sensor: return sim::Motion::general;
    }
    return sim::Motion::general;
}

// Skin tones from pale to dark, and mugs (white, red, blue, black), BGR.
cv::Scalar occluder_colour(cv::RNG& rng) {
    static constexpr double kSkin[][3] = {{150, 175, 225}, {120, 150, 205}, {95, 125, 180}, {60, 85, 130}};
    static constexpr double kMug[][3] = {{225, 228, 230}, {45, 45, 170}, {150, 95, 40}, {35, 35, 38}};
    const bool skin = rng.uniform(0.0, 1.0) < 0.6;
    const int pick = rng.uniform(0, 4);
    const double jitter = rng.uniform(0.9, 1.1);
    const auto& c = skin ? kSkin[pick] : kMug[pick];
    return cv::Scalar(c[0] * jitter, c[1] * jitter, c[2] * jitter);
}

// The blob's outline at a given scale: an elongated ellipse (a finger, a
// hand's edge, a mug's body seen obliquely) reaching in from outside the
// image, with a rounder lobe at its root (the palm, the mug's handle side).
struct Blob {
    cv::Point2d root;      // outside or on the image border
    cv::Point2d toward;    // unit vector into the image
    double length = 0;     // of the main ellipse's long semi-axis
    double aspect = 2;     // long / short semi-axis
    double lobe = 0.8;     // lobe radius relative to the short semi-axis
};

void draw_blob(cv::Mat& mask, const Blob& b, double scale) {
    mask.setTo(0);
    const double a = b.length * scale, s = a / b.aspect;
    const cv::Point2d centre = b.root + b.toward * (0.55 * a);
    const double angle = std::atan2(b.toward.y, b.toward.x) * 180 / CV_PI;
    // Sub-pixel outline via 4 bits of fixed-point shift, antialiased.
    constexpr int kShift = 4;
    constexpr double kOne = 1 << kShift;
    const auto fixed = [&](cv::Point2d p) { return cv::Point(cvRound(p.x * kOne), cvRound(p.y * kOne)); };
    cv::ellipse(mask, fixed(centre), cv::Size(cvRound(a * kOne), cvRound(s * kOne)), angle, 0, 360, cv::Scalar(255),
                cv::FILLED, cv::LINE_AA, kShift);
    cv::circle(mask, fixed(b.root), cvRound(s * b.lobe * 1.6 * kOne), cv::Scalar(255), cv::FILLED, cv::LINE_AA, kShift);
}

// The third camera model's draws for frame i, from a stream of its own (the
// other categories' draws stay as they were). The optics are sharp at the
// photosite's scale (a phone lens resolves about its sensor's pitch); the
// screen shows its RGB stripes in half the frames.
sim::SensorPipeline sensor_pipeline(std::uint64_t seed, int frame, sim::Degradation& d) {
    cv::RNG rng(mix_seed(seed, static_cast<std::uint64_t>(frame), 7));
    sim::SensorPipeline p;
    p.demosaic = static_cast<sim::Demosaic>(rng.uniform(0, 3));
    p.scaler = static_cast<sim::Scaler>(rng.uniform(0, 3));
    p.read_noise = rng.uniform(1.0, 3.0);
    p.shot_noise = rng.uniform(0.15, 0.4);
    p.sharpen = rng.uniform(0.0, 1.0);
    p.jpeg_quality = rng.uniform(70, 93);
    p.seed = mix_seed(seed, static_cast<std::uint64_t>(frame), 8);
    d.defocus_sigma_px = rng.uniform(0.3, 1.0);
    d.subpixels = rng.uniform(0.0, 1.0) < 0.5;
    d.noise_sigma = 0;
    d.jpeg_quality = 0;
    return p;
}

}  // namespace

const char* to_string(Category category) {
    switch (category) {
    case Category::near_far: return "near_far";
    case Category::horizontal: return "horizontal";
    case Category::rotation: return "rotation";
    case Category::perspective: return "perspective";
    case Category::general: return "general";
    case Category::occlusion: return "occlusion";
    case Category::low_light: return "low_light";
    case Category::smeared: return "smeared";
    case Category::distant: return "distant";
    case Category::compressed: return "compressed";
    case Category::tiny: return "tiny";
    case Category::pixel_grid: return "pixel_grid";
    case Category::ruled: return "ruled";
    case Category::sensor: return "sensor";
    }
    return "?";
}

bool is_plain(Category category) {
    return category != Category::occlusion && category != Category::low_light && category != Category::smeared &&
           category != Category::compressed && category != Category::pixel_grid && category != Category::ruled &&
           category != Category::sensor;
}

std::optional<Category> category_from_string(const std::string& name) {
    for (Category c : kAllCategories)
        if (name == to_string(c)) return c;
    return std::nullopt;
}

std::vector<FrameRecipe> category_recipes(const Scene& scene, Category category, int frames, std::uint64_t seed) {
    // general, occlusion, low_light, smeared and compressed share the seed and
    // hence the poses and the everyday degradations: what they add is then
    // all that differs.
    // distant: the near_far sweep from 650 to 1100 mm (modules of 4-7 px
    // at 640 x 480); tiny: from 1000 to 1400 mm (3-4 px at 640 x 480, where
    // the module edges of a grid line lie closer than the edgels' reach).
    // pixel_grid: 100 to 280 mm, where a screen pixel is 0.5-1.4 image px
    // at 640 x 480 (1-2.8 at 1280 x 720) and aliases most.
    const sim::MotionRange range = category == Category::distant      ? sim::MotionRange{900, 650, 1100, 60}
                                   : category == Category::tiny       ? sim::MotionRange{1200, 1000, 1400, 60}
                                   : category == Category::pixel_grid ? sim::MotionRange{170, 100, 280, 40}
                                                                      : scene.range;
    const std::vector<sim::CameraPose> poses =
        sim::pose_trajectory(motion_of(category), frames, scene.screen.pixels, seed, range);
    cv::RNG extra(mix_seed(seed, static_cast<std::uint64_t>(category), 6));
    std::vector<FrameRecipe> out;
    for (int i = 0; i < frames; ++i) {
        FrameRecipe r;
        r.index = i;
        r.pose = poses[static_cast<std::size_t>(i)];
        r.screen = category == Category::ruled
                       ? sim::ScreenKind::spreadsheet
                       : sim::kEverydayScreenKinds[static_cast<std::size_t>(i) % sim::kEverydayScreenKinds.size()];
        r.degradation = everyday_degradation(seed, i);
        if (category == Category::low_light) {
            // An evening room: the phone underexposes the screen, its tone
            // curve crushes the mid-tones, and the gain amplifies the noise.
            r.degradation.exposure = 0.35;
            r.degradation.gamma = 1.2;
            r.degradation.noise_sigma = 6;
        }
        if (category == Category::occlusion) r.occluder_seed = mix_seed(seed, static_cast<std::uint64_t>(i), 3);
        // Both drawn for every category, so the stream is the same for all.
        const double smear_px = extra.uniform(4.0, 12.0), smear_deg = extra.uniform(0.0, 180.0);
        const int quality = extra.uniform(25, 56);
        if (category == Category::smeared) {
            // A hand moving the phone during a long exposure: 4-12 px at
            // 640 x 480, 12-36 px at 1920 x 1080.
            r.degradation.motion_blur_px = smear_px;
            r.degradation.motion_angle_deg = smear_deg;
            r.smear_scales_with_width = true;
        }
        // A screen recording or a video call's frame: low-quality JPEG.
        if (category == Category::compressed) r.degradation.jpeg_quality = quality;
        if (category == Category::pixel_grid) r.degradation.pixel_grid = true;
        if (category == Category::sensor) r.sensor = sensor_pipeline(seed, i, r.degradation);
        out.push_back(r);
    }
    return out;
}

std::vector<FrameRecipe> pulsing_recipes(const Scene& scene, sim::ScreenKind kind, int frames, std::uint64_t seed) {
    const auto k = static_cast<std::uint64_t>(kind);
    cv::RNG rng(mix_seed(seed, k, 4));
    // Slow swings of different periods so that pitch, distance and pulse
    // phase meet in many combinations; small fast terms for the hand's tremor.
    const double pitch_period = rng.uniform(5.0, 7.0), pitch_phase = rng.uniform(0.0, kTwoPi);
    const double dist_period = rng.uniform(3.5, 5.0), dist_phase = rng.uniform(0.0, kTwoPi);
    const double aim_period = rng.uniform(8.0, 12.0), aim_phase = rng.uniform(0.0, kTwoPi);
    const double yaw_period = rng.uniform(6.0, 9.0), yaw_phase = rng.uniform(0.0, kTwoPi);
    const double tremor_hz = rng.uniform(1.5, 3.0), tremor_phase = rng.uniform(0.0, kTwoPi);
    const double rest_roll = rng.uniform(-8.0, 8.0);
    const double w = scene.screen.pixels.width, h = scene.screen.pixels.height;

    std::vector<FrameRecipe> out;
    for (int i = 0; i < frames; ++i) {
        const double t = i / sim::kFps;
        const double tremor = std::sin(kTwoPi * tremor_hz * t + tremor_phase);
        FrameRecipe r;
        r.index = i;
        r.screen = kind;
        r.pose.pitch_deg = 20 + 40 * std::sin(kTwoPi * t / pitch_period + pitch_phase) + 0.7 * tremor;
        r.pose.distance_mm = 250 + 150 * std::sin(kTwoPi * t / dist_period + dist_phase) + 2 * tremor;
        r.pose.yaw_deg = 12 * std::sin(kTwoPi * t / yaw_period + yaw_phase);
        r.pose.roll_deg = rest_roll + 0.8 * tremor;
        r.pose.aim_screen_px = {w * (0.5 + 0.2 * std::sin(kTwoPi * t / aim_period + aim_phase)),
                                h * (0.5 + 0.15 * std::cos(kTwoPi * t / aim_period + aim_phase))};
        r.degradation = everyday_degradation(mix_seed(seed, k, 5), i);
        out.push_back(r);
    }
    return out;
}

double pulsing_opacity(int frame) { return sim::pulse_opacity(frame / sim::kFps, 0.1, 0.4, 1.5); }

Frame shoot(const Scene& scene, const FrameRecipe& recipe, const cv::Mat& mixed_screen, cv::Size resolution) {
    return shoot(scene, recipe, sim::ScreenSource(mixed_screen, scene.screen), resolution);
}

Frame shoot(const Scene& scene, const FrameRecipe& recipe, const sim::ScreenSource& mixed_screen, cv::Size resolution) {
    const sim::ScreenGeometry& geometry = mixed_screen.geometry();
    CV_Assert(geometry.pixels == scene.screen.pixels && geometry.width_mm == scene.screen.width_mm);
    sim::Degradation degradation = recipe.degradation;
    if (recipe.smear_scales_with_width) degradation.motion_blur_px *= resolution.width / 640.0;
    if (recipe.sensor) {
        // A 4K-wide sensor (1920 photosites after 2 x 2 binning for 640 px).
        sim::SensorPipeline pipeline = *recipe.sensor;
        pipeline.scale = resolution.width >= 1920 ? 2 : 3;
        degradation.motion_blur_px *= pipeline.scale;
        const sim::CameraModel sensor{resolution * pipeline.scale, scene.hfov_deg};
        sim::Shot shot = sim::photograph(mixed_screen, sensor, recipe.pose, degradation, scene.module_px);
        Frame f;
        f.centre_screen_px = shot.centre_screen_px;
        f.centre_on_screen = shot.centre_on_screen;
        f.module_px_in_image = shot.module_px_in_image / pipeline.scale;
        cv::cvtColor(sim::develop(shot.bgr, pipeline), f.grey, cv::COLOR_BGR2GRAY);
        return f;
    }
    const sim::CameraModel camera{resolution, scene.hfov_deg};
    sim::Shot shot = sim::photograph(mixed_screen, camera, recipe.pose, degradation, scene.module_px);
    Frame f;
    f.centre_screen_px = shot.centre_screen_px;
    f.centre_on_screen = shot.centre_on_screen;
    f.module_px_in_image = shot.module_px_in_image;
    if (recipe.occluder_seed) {
        // The occluder is nearer than the screen, so it is at least as
        // defocused; its edge is softened by about the same blur.
        f.occluded_fraction = draw_occluder(shot.bgr, *recipe.occluder_seed, recipe.degradation.defocus_sigma_px,
                                            recipe.degradation.noise_sigma);
        cv::cvtColor(shot.bgr, f.grey, cv::COLOR_BGR2GRAY);
    } else {
        f.grey = shot.grey;
    }
    return f;
}

double draw_occluder(cv::Mat& bgr, std::uint64_t seed, double edge_sigma_px, double noise_sigma) {
    CV_Assert(bgr.type() == CV_8UC3);
    cv::RNG rng(seed);
    const double w = bgr.cols, h = bgr.rows;
    const cv::Point2d centre(w / 2, h / 2);
    // The centre stays clear by a margin: an occluder right at the aim
    // point would make the frame unanswerable for every method.
    const double clear_radius = 0.06 * std::min(w, h);
    const cv::Scalar colour = occluder_colour(rng);
    const cv::Point2d light = [&] {
        const double a = rng.uniform(0.0, kTwoPi);
        return cv::Point2d(std::cos(a), std::sin(a));
    }();

    cv::Mat mask(bgr.size(), CV_8U);
    double covered = 0;
    bool placed = false;
    for (int attempt = 0; attempt < 60 && !placed; ++attempt) {
        const double target = rng.uniform(0.15, 0.35);
        const int side = rng.uniform(0, 4);  // left, top, right, bottom
        const double along = rng.uniform(0.1, 0.9);
        Blob b;
        switch (side) {
        case 0: b.root = {-0.05 * w, along * h}; break;
        case 1: b.root = {along * w, -0.05 * h}; break;
        case 2: b.root = {1.05 * w, along * h}; break;
        default: b.root = {along * w, 1.05 * h}; break;
        }
        // Pointing roughly at the centre, but off it.
        const double aim_angle = std::atan2(centre.y - b.root.y, centre.x - b.root.x) + rng.uniform(-0.6, 0.6);
        b.toward = {std::cos(aim_angle), std::sin(aim_angle)};
        b.aspect = rng.uniform(1.4, 2.6);
        b.lobe = rng.uniform(0.6, 1.0);
        b.length = std::sqrt(target * w * h / CV_PI * b.aspect);
        // Two corrections of the scale towards the target area (the parts
        // outside the image do not count), then accept or try elsewhere.
        double scale = 1;
        for (int fit = 0; fit < 3; ++fit) {
            draw_blob(mask, b, scale);
            covered = cv::countNonZero(mask) / (w * h);
            if (covered <= 0) break;
            if (fit < 2) scale *= std::sqrt(target / covered);
        }
        cv::Mat clear = cv::Mat::zeros(mask.size(), CV_8U);
        cv::circle(clear, centre, cvRound(clear_radius), cv::Scalar(255), cv::FILLED);
        cv::Mat overlap;
        cv::bitwise_and(mask, clear, overlap);
        placed = covered >= 0.15 && covered <= 0.35 && cv::countNonZero(overlap) == 0;
    }
    if (!placed) return 0;

    // Soft edge, shading from one side, sensor noise: a flat sharp-edged
    // patch would be an easier edge than a real hand.
    cv::Mat alpha;
    mask.convertTo(alpha, CV_32F, 1.0 / 255);
    if (edge_sigma_px > 0) cv::GaussianBlur(alpha, alpha, cv::Size(), edge_sigma_px + 0.5);
    cv::Mat image;
    bgr.convertTo(image, CV_32FC3);
    cv::Mat noise(bgr.size(), CV_32FC3);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, std::max(noise_sigma, 1.0));
    const double reach = std::hypot(w, h) / 2;
    for (int y = 0; y < bgr.rows; ++y) {
        const float* a = alpha.ptr<float>(y);
        const cv::Vec3f* n = noise.ptr<cv::Vec3f>(y);
        cv::Vec3f* px = image.ptr<cv::Vec3f>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            if (a[x] <= 0) continue;
            const double shade = 0.85 + 0.2 * ((x - centre.x) * light.x + (y - centre.y) * light.y) / reach;
            for (int c = 0; c < 3; ++c) {
                const double occ = colour[c] * shade + n[x][c];
                px[x][c] = static_cast<float>((1 - a[x]) * px[x][c] + a[x] * occ);
            }
        }
    }
    image.convertTo(bgr, CV_8UC3);
    return covered;
}

}  // namespace umf::bench
