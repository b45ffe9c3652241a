// A camera frame as the grey image the detector reads, through libumf's own
// luma so every requester (this one, the web page) sees the same grey.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "shared/detect/image.hpp"

namespace umf::requester {

// A view of `px` (8-bit grey, BGR or BGRA) in grey; `luma` holds the
// converted pixels and must outlive the view. Sets `why` and returns an empty
// view for any other pixel type.
GreyView grey_view(const cv::Mat& px, std::vector<std::uint8_t>& luma, std::string& why);

}  // namespace umf::requester
