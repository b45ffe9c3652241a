#include "tests/sim/video_compression.hpp"

#include <opencv2/imgproc.hpp>

#include "tests/sim/degradation.hpp"

namespace umf::sim {

cv::Mat video_compress(const cv::Mat& bgr8, const VideoCompression& c) {
    CV_Assert(bgr8.type() == CV_8UC3);
    cv::Mat out = bgr8.clone();
    if (c.flat_threshold > 0) {
        cv::Mat grey;
        cv::cvtColor(bgr8, grey, cv::COLOR_BGR2GRAY);
        for (int y = 0; y < out.rows; y += kMacroblockPx)
            for (int x = 0; x < out.cols; x += kMacroblockPx) {
                const cv::Rect block(x, y, std::min(kMacroblockPx, out.cols - x), std::min(kMacroblockPx, out.rows - y));
                cv::Scalar mean, sd;
                cv::meanStdDev(grey(block), mean, sd);
                if (sd[0] < c.flat_threshold) out(block).setTo(cv::mean(bgr8(block)));
            }
    }
    if (c.quality > 0) out = jpeg_roundtrip(out, c.quality);
    return out;
}

}  // namespace umf::sim
