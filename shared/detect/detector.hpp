// The detector: finds the field in a grey camera frame and the field point
// under the aim point (the image centre unless given). The pipeline, one
// stage per file:
//   1. edgels on sparse scanlines            (edgels.hpp)
//   2. two vanishing points                  (vanishing_points.hpp)
//   3. the grid lines of both families       (grid_lines.hpp)
//   4. grid homography from line crossings   (homography.hpp)
//   5. module values or edge signs           (classify.hpp)
//   6. window lookup and placement vote      (window_index.hpp, placement_vote.hpp)
// A wrong place is worse than none: every stage may end in "not found".
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "detect/classify.hpp"
#include "detect/edgels.hpp"
#include "detect/grid_lines.hpp"
#include "detect/image.hpp"
#include "detect/placement_vote.hpp"
#include "detect/vanishing_points.hpp"
#include "detect/window_index.hpp"

namespace umf {

struct DetectorOptions {
    EdgelOptions edgels;
    VanishingOptions vanishing;
    GridLineOptions grid;
    ClassifyOptions classify;
    VoteOptions vote;
    double corner_tolerance_px = 1.5;  // robust grid homography
};

struct StageTimes {
    double edgels_ms = 0, vanishing_ms = 0, grid_ms = 0, classify_ms = 0, vote_ms = 0, total_ms = 0;
};

struct Detection {
    bool found = false;
    Eigen::Matrix3d image_to_field = Eigen::Matrix3d::Identity();
    Eigen::Vector2d aim_image = Eigen::Vector2d::Zero();
    Eigen::Vector2d aim_field = Eigen::Vector2d::Zero();  // (u, v) in modules
    int windows = 0;          // windows that agreed on the place
    double confidence = 0;    // fraction of the read modules or edges the place explains
    StageTimes times;
    long pixels_visited = 0;
    std::string failure;      // the stage that ended the search, when not found
};

class Detector {
public:
    // Throws std::invalid_argument for a field that is not 4-orientable.
    explicit Detector(const Field& field, DetectorOptions options = {});

    Detection detect(const GreyView& image) const;
    Detection detect(const GreyView& image, const Eigen::Vector2d& aim) const;

    const Field& field() const { return index_.field(); }

private:
    bool grid_homography(const GridLineFamily& rows_family, const GridLineFamily& cols_family, const GreyView& image,
                         Eigen::Matrix3d& grid_to_image, int& rows, int& cols) const;

    WindowIndex index_;
    DetectorOptions options_;
};

}  // namespace umf
