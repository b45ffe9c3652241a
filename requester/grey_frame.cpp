#include "requester/grey_frame.hpp"

namespace umf::requester {

GreyView grey_view(const cv::Mat& px, std::vector<std::uint8_t>& luma, std::string& why) {
    if (px.depth() != CV_8U || (px.channels() != 1 && px.channels() != 3 && px.channels() != 4)) {
        why = "pixels of OpenCV type " + std::to_string(px.type()) + " are not 8-bit grey, BGR or BGRA";
        return {};
    }
    const auto stride = static_cast<std::ptrdiff_t>(px.step);
    // An image beyond the detector's limit is not converted (that could take
    // gigabytes): a view of its raw bytes, which are all in bounds, lets the
    // detector reject it with its own "invalid image" reason.
    if (px.channels() == 1 || px.cols > kMaxImageSideForDetection || px.rows > kMaxImageSideForDetection)
        return {px.data, px.cols, px.rows, stride};
    return to_luma({px.data, px.cols, px.rows, stride, px.channels() == 3 ? PixelOrder::bgr : PixelOrder::bgra},
                   luma);
}

}  // namespace umf::requester
