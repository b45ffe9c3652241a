// A phone camera photographing the screen: a pinhole camera in front of the
// screen plane, antialiased rendering, then blur, glare, exposure, noise and
// JPEG (degradation.hpp), with exact ground truth for every image point.
//
// World frame, in millimetres: the screen is the plane z = 0, x to the right
// along the pixel rows, y down, the viewer at z < 0; screen pixel coordinates
// (continuous, pixel (x, y) covering [x, x + 1) x [y, y + 1)) times the pixel
// pitch give x and y. Camera frame: x right, y down, z forward (OpenCV's).
// Image coordinates are continuous like the screen's: the centre of image
// pixel (x, y) is (x + 0.5, y + 0.5), the image centre is (w / 2, h / 2).
//
// Pose: the camera stands distance_mm from aim_screen_px and looks at it.
//   pitch > 0: the camera is above the aim point looking down (the screen's
//              upper part is nearer and looks larger);
//   yaw > 0:   the camera is right of the aim point looking left;
//   roll > 0:  the camera turns clockwise about its axis as the user sees it
//              from behind, so the screen appears turned counter-clockwise.
// Yaw is applied about the screen's vertical, then pitch about the camera's
// (still horizontal) x axis, then roll: the camera's x axis stays parallel to
// the screen when roll is 0.
#pragma once

#include <opencv2/core.hpp>

#include "tests/sim/degradation.hpp"
#include "tests/sim/field_mix.hpp"

namespace umf::sim {

class ScreenSource;  // screen_source.hpp

struct ScreenGeometry {
    cv::Size pixels{1920, 1080};
    double width_mm = 527;  // physical width; height follows the pixel aspect (square pixels)
};

struct CameraPose {
    double distance_mm = 300;
    double pitch_deg = 0;
    double yaw_deg = 0;
    double roll_deg = 0;
    cv::Point2d aim_screen_px;
};

struct CameraModel {
    cv::Size resolution{1280, 720};
    double hfov_deg = 65;  // horizontal field of view
};

struct Shot {
    cv::Mat bgr;   // CV_8UC3, camera resolution
    cv::Mat grey;  // CV_8U, from bgr
    // Image px -> screen px, continuous coordinates, not normalised: its third
    // homogeneous output is positive exactly for image points whose ray meets
    // the screen plane in front of the camera.
    cv::Matx33d image_to_screen;
    cv::Point2d centre_screen_px;  // screen point under the image centre
    double screen_px_in_image = 0;   // image pixels per screen pixel around the image centre
    double module_px_in_image = 0;   // screen_px_in_image * screen_module_px_for_gt (0 when that is 0)
    bool centre_on_screen = false;
};

double screen_mm_per_px(const ScreenGeometry& screen);
double focal_px(const CameraModel& camera);
cv::Matx33d intrinsics(const CameraModel& camera);

// The homography taking screen pixels to image pixels, scaled so that its
// third homogeneous output is positive for points in front of the camera.
cv::Matx33d screen_to_image(const ScreenGeometry& screen, const CameraModel& camera, const CameraPose& pose);

// Scale of the screen in the image around a screen point: the square root of
// the local area ratio, the geometric mean of the two axes when the view is
// foreshortened.
double screen_px_in_image_at(const cv::Matx33d& screen_to_image, cv::Point2d screen_px);

// The photograph. screen_bgr must have screen.pixels' size;
// screen_module_px_for_gt only fills module_px_in_image. Depends only on the
// arguments (noise and glare on degradation.seed). Cost at 1280 x 720 from
// a 1920 x 1080 screen, one thread: about 50 ms square-on, 100 ms under
// strong perspective (several mipmap levels) or with subpixels (which
// triples the source, to about 80 MB of floats).
Shot photograph(const cv::Mat& screen_bgr, const ScreenGeometry& screen, const CameraModel& camera,
                const CameraPose& pose, const Degradation& degradation, double screen_module_px_for_gt = 0);
// The same photograph of a screen made ready once for many shots. Without
// the conversion to linear light and the mipmap levels a 640 x 480 shot
// costs about a fifth less (33 against 42 ms), with subpixels 72 % less and
// with the pixel grid 89 % less (measured 2026-12-01, one thread).
Shot photograph(const ScreenSource& screen, const CameraModel& camera, const CameraPose& pose,
                const Degradation& degradation, double screen_module_px_for_gt = 0);

cv::Point2d image_to_screen(const Shot& shot, cv::Point2d image_px);
cv::Point2d image_to_field(const Shot& shot, const FieldPlacement& placement, cv::Point2d image_px);
cv::Point2d field_to_image(const Shot& shot, const FieldPlacement& placement, cv::Point2d field_uv);

}  // namespace umf::sim
