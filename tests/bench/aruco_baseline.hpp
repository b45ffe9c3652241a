// The baseline the umf detector is compared with: OpenCV's ArUco markers
// (contrib module, OpenCV 4.6 API), mixed into the screen the way the field
// is and located the way a marker-based app would: detect the markers, fit
// a homography from their image corners to their known screen positions,
// and map the image centre through it.
//
// Layout: an 8 x 4 grid board of DICT_4X4_250 markers, 180 px each (4 x 4
// bits plus a one-cell border = 6 cells of 30 px, the field's module size)
// with 60 px gaps, centred on the 1920 x 1080 screen. The board's white
// background covers the whole screen, so the board occupies the same area
// as the 64 x 36 field and both methods see the same blend of the same
// content at the same opacity.
#pragma once

#include <opencv2/aruco.hpp>
#include <opencv2/core.hpp>

#include <map>
#include <string>
#include <vector>

namespace umf::bench {

struct ArucoLocation {
    bool found = false;
    cv::Point2d aim_screen_px;  // the screen point under the image centre
    int markers = 0;            // board markers detected
    std::string failure;        // why not found
};

class ArucoBaseline {
public:
    explicit ArucoBaseline(cv::Size screen_px, int cell_px = 30);

    // (1 - opacity) * content + opacity * board, rounded, like mix_field.
    cv::Mat mix(const cv::Mat& screen_bgr, double opacity) const;

    // The screen point under the image centre, from one grey frame. This is
    // the whole per-frame work of the method, the part to time.
    ArucoLocation locate(const cv::Mat& grey) const;

    const cv::Mat& board_image() const { return board_; }
    int marker_count() const { return static_cast<int>(corners_.size()); }

private:
    cv::Ptr<cv::aruco::Dictionary> dictionary_;
    cv::Ptr<cv::aruco::DetectorParameters> parameters_;
    cv::Mat board_;  // CV_8UC3, screen size, white with the markers
    std::map<int, std::vector<cv::Point2f>> corners_;  // id -> screen corners TL, TR, BR, BL
};

}  // namespace umf::bench
