// A phone's 30 fps video encoder at a modest bitrate, as the detector sees
// frames from a video stream rather than from stills: macroblocks whose
// content barely varies are coded flat (the encoder spends no bits on faint
// texture there), which wipes faint patterns out of plain areas and leaves
// steps at the 16 px block borders on gentle gradients; then coarse DCT
// quantisation with 4:2:0 chroma (JPEG at a low quality, which shares the
// 8 x 8 transform and the chroma subsampling with H.264's intra blocks).
// Deterministic: no encoder state, the same frame gives the same output.
#pragma once

#include <opencv2/core.hpp>

namespace umf::sim {

struct VideoCompression {
    int quality = 0;             // 1..100 as JPEG's; 0 = off
    double flat_threshold = 0;   // grey-level standard deviation below which a 16 x 16 macroblock is coded flat
};

inline constexpr int kMacroblockPx = 16;

// 8-bit BGR in and out.
cv::Mat video_compress(const cv::Mat& bgr8, const VideoCompression& compression);

}  // namespace umf::sim
