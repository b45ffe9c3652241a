#include "tests/sim/field_mix.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace umf::sim {

cv::Point2d field_to_screen(const FieldPlacement& placement, cv::Point2d field_uv) {
    return placement.origin + placement.module_px * field_uv;
}

cv::Point2d screen_to_field(const FieldPlacement& placement, cv::Point2d screen_px) {
    return (screen_px - placement.origin) / placement.module_px;
}

FieldPlacement centred_placement(const Field& field, cv::Size screen, double module_px) {
    const cv::Point2d centre(screen.width / 2.0, screen.height / 2.0);
    return {centre - 0.5 * module_px * cv::Point2d(field.width, field.height), module_px};
}

std::vector<cv::Vec3b> palette_bgr(const Field& field) {
    const auto& hex = field.palette.empty() ? grey_palette(field.colors) : field.palette;
    std::vector<cv::Vec3b> out;
    for (const auto& c : hex) {
        if (c.size() != 7 || c[0] != '#') throw std::invalid_argument("palette entry '" + c + "' is not #rrggbb");
        const auto channel = [&](int at) { return static_cast<uchar>(std::stoi(c.substr(at, 2), nullptr, 16)); };
        out.emplace_back(channel(5), channel(3), channel(1));
    }
    return out;
}

namespace {

// First pixel index whose centre has field coordinate >= 0, and one past the
// last whose centre is below `modules`, clipped to [0, pixels].
std::pair<int, int> covered_pixels(double origin, double module_px, int modules, int pixels) {
    const auto first = static_cast<int>(std::ceil(origin - 0.5));
    const auto end = static_cast<int>(std::ceil(origin + module_px * modules - 0.5));
    return {std::clamp(first, 0, pixels), std::clamp(end, 0, pixels)};
}

}  // namespace

cv::Mat mix_field(const cv::Mat& screen_bgr, const Field& field, const FieldPlacement& placement, double opacity) {
    CV_Assert(screen_bgr.type() == CV_8UC3 && placement.module_px > 0);
    const std::vector<cv::Vec3b> palette = palette_bgr(field);
    cv::Mat out = screen_bgr.clone();
    const auto [x0, x1] = covered_pixels(placement.origin.x, placement.module_px, field.width, out.cols);
    const auto [y0, y1] = covered_pixels(placement.origin.y, placement.module_px, field.height, out.rows);

    // Module column of every covered pixel column, computed once per image.
    std::vector<int> column(static_cast<std::size_t>(std::max(0, x1 - x0)));
    for (int x = x0; x < x1; ++x) {
        const double u = screen_to_field(placement, {x + 0.5, 0}).x;
        column[x - x0] = std::clamp(static_cast<int>(std::floor(u)), 0, field.width - 1);
    }
    for (int y = y0; y < y1; ++y) {
        const double v = screen_to_field(placement, {0, y + 0.5}).y;
        const int row = std::clamp(static_cast<int>(std::floor(v)), 0, field.height - 1);
        auto* px = out.ptr<cv::Vec3b>(y);
        for (int x = x0; x < x1; ++x) {
            const cv::Vec3b& colour = palette[field.at(row, column[x - x0])];
            for (int c = 0; c < 3; ++c)
                px[x][c] = cv::saturate_cast<uchar>((1 - opacity) * px[x][c] + opacity * colour[c]);
        }
    }
    return out;
}

}  // namespace umf::sim
