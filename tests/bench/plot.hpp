// Two small chart types for the benchmark's PNGs, drawn with OpenCV's own
// drawing functions so that the benchmark needs nothing beyond what the
// simulator already links: white background, axes with round-number ticks,
// axis labels, a title and a legend to the right of the plot.
#pragma once

#include <opencv2/core.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace umf::bench::plot {

struct Axes {
    std::string title, x_label, y_label;
    std::optional<std::pair<double, double>> y_range;  // default: from the data (bars: from 0)
};

struct Series {
    std::string label;
    std::vector<double> x, y;  // NaN y values leave a hole
    cv::Scalar colour;
    bool dashed = false;
    bool dotted = false;            // short dashes; wins over `dashed`
    bool square_markers = false;    // circles otherwise
    bool triangle_markers = false;  // wins over `square_markers`
};

// Lines through points, each series with its own colour, dash and marker.
cv::Mat line_chart(const Axes& axes, const std::vector<Series>& series, cv::Size size = {960, 600});

// Grouped bars: groups along x (e.g. resolutions), in each one bar per
// series (e.g. method), the value printed above each bar.
struct Bars {
    std::vector<std::string> groups;
    std::vector<std::string> series;
    std::vector<cv::Scalar> colours;           // one per series
    std::vector<std::vector<double>> values;   // [series][group]; NaN = no bar
};

cv::Mat bar_chart(const Axes& axes, const Bars& bars, cv::Size size = {960, 600});

// Distinct colours that stay apart in print, BGR.
cv::Scalar colour(int index);

}  // namespace umf::bench::plot
