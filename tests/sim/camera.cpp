#include "tests/sim/camera.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "tests/sim/homography.hpp"
#include "tests/sim/resample.hpp"
#include "tests/sim/screen_source.hpp"

namespace umf::sim {
namespace {

// Around the screen and its bezel (screen_source.hpp): a dim desk.
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
    return photograph(ScreenSource(screen_bgr, screen), camera, pose, d, screen_module_px_for_gt);
}

Shot photograph(const ScreenSource& source, const CameraModel& camera, const CameraPose& pose, const Degradation& d,
                double screen_module_px_for_gt) {
    const ScreenGeometry& screen = source.geometry();
    Shot shot;
    const cv::Matx33d s2i = screen_to_image(screen, camera, pose);
    // inv() of a depth-scaled homography has third output 1 / depth: also
    // positive exactly for image rays that meet the screen plane in front.
    shot.image_to_screen = s2i.inv();

    const ScreenRendering rendering = rendering_for(d);
    const ScreenSource::Light& light_source = source.light(rendering);
    const double aliasing = rendering == ScreenRendering::pixel_grid ? kGridAliasing
                            : rendering == ScreenRendering::subpixels ? kStripeAliasing
                                                                      : 0.0;
    cv::Mat light = sample_perspective(light_source.mipmap, light_source.from_screen * shot.image_to_screen,
                                       camera.resolution, to_linear(kDeskBgr), aliasing);

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
