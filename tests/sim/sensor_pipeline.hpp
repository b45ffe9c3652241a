// A third camera model for the tuning set: the path a phone's video frame
// takes from a sensor several times finer than the frame. A phone asked for
// 640 x 480 or 1280 x 720 reads a 4K-wide sensor behind a colour filter
// array (one colour per photosite, RGGB), fills in the missing colours
// (demosaicing), adds its noise per photosite, and scales the result down
// with whatever its scaler does: skip photosites, a two-tap bilinear filter
// that aliases when shrinking by 2 or more, or a proper area average. Where
// the screen's pixels come near the photosite pitch, the filter array and
// the scaler fold the screen's pixel structure into moire of their own,
// which neither the first model (photographed at the frame's size) nor the
// held-out one (pixel structure sampled at the frame's size) makes.
//
// `develop` takes the optical image at sensor resolution (`photograph` at
// `scale` times the frame's size, without noise or JPEG) and returns the
// frame. Coordinates stay pixel-centre aligned: frame pixel (x, y) covers
// sensor pixels [x, x+1) * scale, so the sensor shot's ground truth divided
// by `scale` is the frame's.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>

namespace umf::sim {

enum class Demosaic { bilinear, edge_aware, vng };
enum class Scaler { skip, bilinear, area };

struct SensorPipeline {
    int scale = 3;                    // sensor pixels per frame pixel, each way (2..4)
    Demosaic demosaic = Demosaic::bilinear;
    Scaler scaler = Scaler::bilinear;
    double read_noise = 1.5;          // grey levels per photosite
    double shot_noise = 0.25;         // grey levels per sqrt(level) per photosite
    double sharpen = 0.5;             // unsharp-mask amount on the frame (0: none)
    int jpeg_quality = 85;            // 0: none
    std::uint64_t seed = 1;
};

// The RGGB mosaic of an 8-bit BGR image (R at even rows and columns, B at
// odd ones, G between), as one 8-bit channel.
cv::Mat bayer_mosaic(const cv::Mat& bgr8);

// The frame a phone makes from `sensor_bgr8` (CV_8UC3, whose size is the
// frame's times `p.scale`): mosaic, per-photosite noise, demosaicing, the
// scaler, sharpening, JPEG. Depends only on the arguments.
cv::Mat develop(const cv::Mat& sensor_bgr8, const SensorPipeline& p);

}  // namespace umf::sim
