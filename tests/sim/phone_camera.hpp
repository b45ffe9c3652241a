// A second camera model, nearer to real phones than camera.hpp's
// photograph(): the same pinhole geometry and antialiased rendering, then
// what camera.hpp leaves out, each from its own file:
//   - the screen's pixel structure (pixel_structure.hpp), point-sampled
//     before any optical blur, so it is resolved close up and aliases into
//     moire at middle distances;
//   - a rolling shutter under hand motion (rolling_shutter.hpp);
//   - motion blur along curved paths (curved_motion.hpp);
//   - metered exposure with auto-exposure hunting, signal-dependent sensor
//     noise, the phone's denoise / local tone mapping / sharpening
//     (phone_processing.hpp);
//   - video compression of a 30 fps stream (video_compression.hpp).
// Depends only on the arguments.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>

#include "tests/sim/camera.hpp"
#include "tests/sim/curved_motion.hpp"
#include "tests/sim/phone_processing.hpp"
#include "tests/sim/pixel_structure.hpp"
#include "tests/sim/rolling_shutter.hpp"
#include "tests/sim/video_compression.hpp"

namespace umf::sim {

struct PhoneShot {
    std::optional<PixelStructure> structure;  // set: the screen's pixel structure shows
    double bezel_mm = 5;
    PoseVelocity velocity;                     // the hand's motion during the frame
    double readout_s = 0;                      // rolling shutter: first row to last
    double defocus_sigma_px = 0;
    CurvedBlur blur;
    double glare = 0;                          // as Degradation::glare
    double metering_target = 0.3;              // mean linear light the metering aims the frame's centre at
    double exposure_scale = 1;                 // on top of the metering: < 1 underexposes (low light)
    double hunt = 1;                           // auto-exposure hunting factor (exposure_hunt)
    double read_noise = 2;                     // grey levels, in output values
    double shot_noise = 0;                     // grey levels at full white, scaling with sqrt(light)
    PhoneProcessing processing;
    VideoCompression compression;
    std::uint64_t seed = 1;
};

// The photograph, with the same ground truth as photograph()'s (the image
// centre's row is exposed at `pose`).
Shot photograph_phone(const cv::Mat& screen_bgr, const ScreenGeometry& screen, const CameraModel& camera,
                      const CameraPose& pose, const PhoneShot& settings, double screen_module_px_for_gt = 0);

}  // namespace umf::sim
