#include "tests/bench/aruco_baseline.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace umf::bench {
namespace {

constexpr int kCellsPerMarker = 6;  // 4 x 4 bits and the one-cell black border
constexpr int kGapCells = 2;
// Below two markers RANSAC has nothing to vote with; the four corners of a
// single marker define the homography exactly.
constexpr int kMinPointsForRansac = 8;
constexpr double kRansacImagePx = 3.0;

}  // namespace

ArucoBaseline::ArucoBaseline(cv::Size screen_px, int cell_px)
    : dictionary_(cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_250)),
      parameters_(cv::aruco::DetectorParameters::create()) {
    const int marker_px = kCellsPerMarker * cell_px, gap_px = kGapCells * cell_px, pitch = marker_px + gap_px;
    const int cols = (screen_px.width + gap_px) / pitch, rows = (screen_px.height + gap_px) / pitch;
    // GridBoard fixes the ids and their order (row-major from firstMarker);
    // the positions are laid out here in screen pixels (y down), so that the
    // corners below are exactly where the markers are drawn.
    const cv::Ptr<cv::aruco::GridBoard> board =
        cv::aruco::GridBoard::create(cols, rows, static_cast<float>(marker_px), static_cast<float>(gap_px), dictionary_);
    const cv::Point origin((screen_px.width - (cols * pitch - gap_px)) / 2, (screen_px.height - (rows * pitch - gap_px)) / 2);

    board_ = cv::Mat(screen_px, CV_8UC3, cv::Scalar::all(255));
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const int id = board->ids[static_cast<std::size_t>(r * cols + c)];
            cv::Mat marker;
            cv::aruco::drawMarker(dictionary_, id, marker_px, marker, 1);
            const cv::Rect at(origin.x + c * pitch, origin.y + r * pitch, marker_px, marker_px);
            cv::cvtColor(marker, board_(at), cv::COLOR_GRAY2BGR);
            // Continuous screen coordinates: the outer corners of the border.
            const auto x0 = static_cast<float>(at.x), y0 = static_cast<float>(at.y), s = static_cast<float>(marker_px);
            corners_[id] = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
        }
}

cv::Mat ArucoBaseline::mix(const cv::Mat& screen_bgr, double opacity) const {
    CV_Assert(screen_bgr.type() == CV_8UC3 && screen_bgr.size() == board_.size());
    cv::Mat out;
    cv::addWeighted(screen_bgr, 1 - opacity, board_, opacity, 0, out);
    return out;
}

ArucoLocation ArucoBaseline::locate(const cv::Mat& grey) const {
    ArucoLocation out;
    std::vector<std::vector<cv::Point2f>> found;
    std::vector<int> ids;
    cv::aruco::detectMarkers(grey, dictionary_, found, ids, parameters_);

    std::vector<cv::Point2f> screen_pts, image_pts;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const auto known = corners_.find(ids[i]);
        if (known == corners_.end()) continue;  // a misread id outside the board
        ++out.markers;
        for (int k = 0; k < 4; ++k) {
            screen_pts.push_back(known->second[static_cast<std::size_t>(k)]);
            // OpenCV puts pixel centres at integers; the simulator at +0.5.
            image_pts.push_back(found[i][static_cast<std::size_t>(k)] + cv::Point2f(0.5f, 0.5f));
        }
    }
    if (out.markers == 0) {
        out.failure = ids.empty() ? "no markers" : "only ids outside the board";
        return out;
    }
    // Screen -> image, so that RANSAC's threshold is in image pixels, then
    // inverted for the centre.
    const bool ransac = static_cast<int>(screen_pts.size()) >= kMinPointsForRansac;
    const cv::Mat s2i = cv::findHomography(screen_pts, image_pts, ransac ? cv::RANSAC : 0, kRansacImagePx);
    if (s2i.empty()) {
        out.failure = "no homography";
        return out;
    }
    const cv::Matx33d i2s = cv::Matx33d(s2i).inv();
    const cv::Vec3d c = i2s * cv::Vec3d(grey.cols / 2.0, grey.rows / 2.0, 1);
    const cv::Vec3d corner = i2s * cv::Vec3d(image_pts[0].x, image_pts[0].y, 1);
    // The centre maps to the screen only on the same side of the horizon as
    // the markers.
    if (c[2] * corner[2] <= 0) {
        out.failure = "aim point beyond the horizon";
        return out;
    }
    out.aim_screen_px = {c[0] / c[2], c[1] / c[2]};
    out.found = true;
    return out;
}

}  // namespace umf::bench
