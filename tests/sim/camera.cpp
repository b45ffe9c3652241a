#include "tests/sim/camera.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "tests/sim/homography.hpp"
#include "tests/sim/resample.hpp"

namespace umf::sim {
namespace {

// Around the screen: a thin black bezel, then a dim desk. The bezel gives
// the detector the real-world distraction of a strong dark frame.
constexpr double kBezelMm = 8;
const cv::Vec3b kBezelBgr(18, 18, 18);
const cv::Vec3b kDeskBgr(40, 52, 66);
// Octaves of stripe detail let through unfiltered with subpixels (see
// sample_perspective). Chosen by eye: moire shows as faint coloured bands,
// as in phone shots of LCDs, instead of none (0) or swamping the picture
// (point sampling).
constexpr double kStripeAliasing = 1.0;
// With the pixel grid, a sensor without an optical low-pass filter in front
// of a screen whose pixels are about its own: two octaves alias.
constexpr double kGridAliasing = 2.0;

double radians(double deg) { return deg * CV_PI / 180; }

cv::Matx33d rot_x(double a) { return {1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a)}; }
cv::Matx33d rot_y(double a) { return {std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)}; }
cv::Matx33d rot_z(double a) { return {std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1}; }

// Columns are the camera's axes in world coordinates. The signs make the
// pose conventions of camera.hpp come out: rot_x(-pitch) tips the optical
// axis towards +y (down the screen) for a camera above the aim point, and
// rot_y(-yaw) towards -x for a camera on the right.
cv::Matx33d camera_to_world(const CameraPose& pose) {
    return rot_y(-radians(pose.yaw_deg)) * rot_x(-radians(pose.pitch_deg)) * rot_z(radians(pose.roll_deg));
}

cv::Mat pad(const cv::Mat& image, int left_right, int top_bottom, const cv::Scalar& value) {
    cv::Mat out;
    cv::copyMakeBorder(image, out, top_bottom, top_bottom, left_right, left_right, cv::BORDER_CONSTANT, value);
    return out;
}

// The screen in linear light with its bezel, ready for sampling, and the
// map from screen coordinates to its pixel coordinates. With subpixels it is
// the striped screen, three times as wide, so that the sampling averages
// real stripes, as the camera's pixels do.
struct ScreenSource {
    cv::Mat linear;
    cv::Matx33d from_screen;
};

ScreenSource screen_source(const cv::Mat& screen_bgr, int bezel_px, bool subpixels, bool grid) {
    if (grid) {
        const cv::Vec3f bezel = to_linear(kBezelBgr);
        return {pad(pixel_grid(to_linear(screen_bgr)), 3 * bezel_px, 3 * bezel_px, cv::Scalar(bezel)),
                scaling(3, 3) * translation(bezel_px, bezel_px)};
    }
    if (!subpixels)
        return {to_linear(pad(screen_bgr, bezel_px, bezel_px, cv::Scalar(kBezelBgr))), translation(bezel_px, bezel_px)};
    const cv::Vec3f bezel = to_linear(kBezelBgr);
    return {pad(subpixel_stripes(to_linear(screen_bgr)), 3 * bezel_px, bezel_px, cv::Scalar(bezel)),
            scaling(3, 1) * translation(bezel_px, bezel_px)};
}

}  // namespace

double screen_mm_per_px(const ScreenGeometry& screen) { return screen.width_mm / screen.pixels.width; }

double focal_px(const CameraModel& camera) { return camera.resolution.width / 2.0 / std::tan(radians(camera.hfov_deg) / 2); }

cv::Matx33d intrinsics(const CameraModel& camera) {
    const double f = focal_px(camera);
    // Continuous coordinates: the principal point is the image centre.
    return {f, 0, camera.resolution.width / 2.0, 0, f, camera.resolution.height / 2.0, 0, 0, 1};
}

cv::Matx33d screen_to_image(const ScreenGeometry& screen, const CameraModel& camera, const CameraPose& pose) {
    const double mm = screen_mm_per_px(screen);
    const cv::Matx33d rcw = camera_to_world(pose);
    const cv::Vec3d aim(pose.aim_screen_px.x * mm, pose.aim_screen_px.y * mm, 0);
    const cv::Vec3d optical_axis(rcw(0, 2), rcw(1, 2), rcw(2, 2));
    const cv::Vec3d centre = aim - pose.distance_mm * optical_axis;
    const cv::Matx33d r = rcw.t();  // world -> camera
    const cv::Vec3d t = -(r * centre);
    // For plane points (x, y, 0): camera = x r1 + y r2 + t, so [r1 r2 t]. Its
    // third output is the point's depth, positive in front of the camera,
    // and K keeps that, so the homography's third component is the depth.
    const cv::Matx33d plane_to_camera(r(0, 0), r(0, 1), t[0], r(1, 0), r(1, 1), t[1], r(2, 0), r(2, 1), t[2]);
    return intrinsics(camera) * plane_to_camera * scaling(mm, mm);
}

double screen_px_in_image_at(const cv::Matx33d& s2i, cv::Point2d screen_px) {
    return std::sqrt(std::abs(cv::determinant(jacobian(s2i, screen_px))));
}

Shot photograph(const cv::Mat& screen_bgr, const ScreenGeometry& screen, const CameraModel& camera,
                const CameraPose& pose, const Degradation& d, double screen_module_px_for_gt) {
    CV_Assert(screen_bgr.type() == CV_8UC3 && screen_bgr.size() == screen.pixels);
    Shot shot;
    const cv::Matx33d s2i = screen_to_image(screen, camera, pose);
    // inv() of a depth-scaled homography has third output 1 / depth: also
    // positive exactly for image rays that meet the screen plane in front.
    shot.image_to_screen = s2i.inv();

    const int bezel_px = static_cast<int>(std::lround(kBezelMm / screen_mm_per_px(screen)));
    const ScreenSource source = screen_source(screen_bgr, bezel_px, d.subpixels, d.pixel_grid);
    const double aliasing = d.pixel_grid ? kGridAliasing : d.subpixels ? kStripeAliasing : 0.0;
    cv::Mat light = sample_perspective(source.linear, source.from_screen * shot.image_to_screen, camera.resolution,
                                       to_linear(kDeskBgr), aliasing);

    // Order of a real camera: the lens blurs the light (defocus, shake during
    // the exposure), reflections add light on the way, the exposure scales
    // all of it, the tone curve encodes it, and noise and JPEG come last.
    apply_optics(light, d);
    apply_glare(light, d.glare, d.seed);
    if (d.exposure != 1.0) light *= d.exposure;
    shot.bgr = to_output(light, d.gamma, d.noise_sigma, d.seed);
    if (d.jpeg_quality > 0) shot.bgr = jpeg_roundtrip(shot.bgr, d.jpeg_quality);
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

cv::Point2d image_to_screen(const Shot& shot, cv::Point2d image_px) { return apply(shot.image_to_screen, image_px); }

cv::Point2d image_to_field(const Shot& shot, const FieldPlacement& placement, cv::Point2d image_px) {
    return screen_to_field(placement, image_to_screen(shot, image_px));
}

cv::Point2d field_to_image(const Shot& shot, const FieldPlacement& placement, cv::Point2d field_uv) {
    return apply(shot.image_to_screen.inv(), field_to_screen(placement, field_uv));
}

}  // namespace umf::sim
