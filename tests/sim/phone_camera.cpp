#include "tests/sim/phone_camera.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "tests/sim/homography.hpp"
#include "tests/sim/resample.hpp"

namespace umf::sim {
namespace {

const cv::Vec3b kBezelBgr(12, 12, 14);
const cv::Vec3b kDeskBgr(58, 62, 70);  // a grey desk, not camera.cpp's brown one

// The structure's gain only on the screen itself, 1 on the bezel and desk.
void apply_structure(cv::Mat& light, const PixelStructure& s, const cv::Matx33d& image_to_screen, cv::Size screen) {
    cv::Mat gain = structure_gain(s, image_to_screen, light.size());
    for (int y = 0; y < light.rows; ++y) {
        auto* g = gain.ptr<cv::Vec3f>(y);
        for (int x = 0; x < light.cols; ++x) {
            const cv::Vec3d q = image_to_screen * cv::Vec3d(x + 0.5, y + 0.5, 1.0);
            const bool on = q[2] > 0 && q[0] / q[2] >= 0 && q[1] / q[2] >= 0 && q[0] / q[2] < screen.width &&
                            q[1] / q[2] < screen.height;
            if (!on) g[x] = cv::Vec3f(1, 1, 1);
        }
    }
    light = light.mul(gain);
}

// Shot noise: variance growing with the light, drawn in linear light
// before the tone curve (in grey levels at full white).
void add_shot_noise(cv::Mat& light, double at_white, std::uint64_t seed) {
    if (at_white <= 0) return;
    cv::Mat n(light.size(), light.type());
    cv::RNG rng(seed * 0xBF58476D1CE4E5B9ull + 0x77);
    rng.fill(n, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(at_white / 255.0));
    cv::Mat root;
    cv::max(light, 0.0, root);
    cv::sqrt(root, root);
    light += n.mul(root);
}

}  // namespace

Shot photograph_phone(const cv::Mat& screen_bgr, const ScreenGeometry& screen, const CameraModel& camera,
                      const CameraPose& pose, const PhoneShot& s, double screen_module_px_for_gt) {
    CV_Assert(screen_bgr.type() == CV_8UC3 && screen_bgr.size() == screen.pixels);
    Shot shot;
    const cv::Matx33d s2i = screen_to_image(screen, camera, pose);
    shot.image_to_screen = s2i.inv();

    const int bezel_px = static_cast<int>(std::lround(s.bezel_mm / screen_mm_per_px(screen)));
    cv::Mat padded;
    cv::copyMakeBorder(screen_bgr, padded, bezel_px, bezel_px, bezel_px, bezel_px, cv::BORDER_CONSTANT, cv::Scalar(kBezelBgr));
    cv::Mat light = sample_perspective(to_linear(padded), translation(bezel_px, bezel_px) * shot.image_to_screen,
                                       camera.resolution, to_linear(kDeskBgr));
    // The sensor samples the emitters before the lens blurs anything.
    if (s.structure) apply_structure(light, *s.structure, shot.image_to_screen, screen.pixels);
    light = rolling_shutter(light, screen, camera, pose, s.velocity, s.readout_s);
    if (s.defocus_sigma_px > 0) cv::GaussianBlur(light, light, {0, 0}, s.defocus_sigma_px, 0, cv::BORDER_REFLECT);
    apply_curved_motion(light, s.blur);
    apply_glare(light, s.glare, s.seed);
    light *= metered_exposure(light, s.metering_target, 0.5, 1.6) * s.exposure_scale * s.hunt;
    add_shot_noise(light, s.shot_noise, s.seed);
    shot.bgr = to_output(light, 1.0, s.read_noise, s.seed);
    shot.bgr = process_phone_frame(shot.bgr, s.processing);
    shot.bgr = video_compress(shot.bgr, s.compression);
    cv::cvtColor(shot.bgr, shot.grey, cv::COLOR_BGR2GRAY);

    const cv::Point2d centre(camera.resolution.width / 2.0, camera.resolution.height / 2.0);
    shot.centre_screen_px = apply(shot.image_to_screen, centre);
    const bool in_front = apply_homogeneous(shot.image_to_screen, centre)[2] > 0;
    shot.centre_on_screen = in_front && shot.centre_screen_px.x >= 0 && shot.centre_screen_px.y >= 0 &&
                            shot.centre_screen_px.x < screen.pixels.width && shot.centre_screen_px.y < screen.pixels.height;
    shot.screen_px_in_image = screen_px_in_image_at(s2i, shot.centre_screen_px);
    shot.module_px_in_image = shot.screen_px_in_image * screen_module_px_for_gt;
    return shot;
}

}  // namespace umf::sim
