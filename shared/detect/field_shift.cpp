#include "shared/detect/field_shift.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "shared/detect/homography.hpp"

namespace umf {

namespace {

// A pixel on the drawn field's module edges: the drawn field's change across
// it, each way (from -1 to 1 of the field's range).
struct DrawnEdge {
    std::ptrdiff_t at = 0;  // y * width + x
    float dx = 0, dy = 0;
};

// The modules where `image_to_field` puts them, a value a pixel from -0.5
// (the field's first colour) to 0.5 (its last); NaN off the field.
std::vector<float> drawn_field(const Field& field, const Eigen::Matrix3d& image_to_field, int width, int height) {
    std::vector<float> drawn(static_cast<std::size_t>(width) * height, std::nanf(""));
    // The view's side of the horizon: that of the frame's centre.
    const double front = (image_to_field * Eigen::Vector3d(width / 2.0, height / 2.0, 1)).z();
    const float scale = field.colors > 1 ? 1.0f / static_cast<float>(field.colors - 1) : 0.0f;
    for (int y = 0; y < height; ++y) {
        Eigen::Vector3d p = image_to_field * Eigen::Vector3d(0, y, 1);
        const Eigen::Vector3d step = image_to_field.col(0);
        float* row = drawn.data() + static_cast<std::size_t>(y) * width;
        for (int x = 0; x < width; ++x, p += step) {
            if (p.z() * front <= 0) continue;
            const double u = p.x() / p.z(), v = p.y() / p.z();
            if (!(u >= 0 && v >= 0 && u < field.width && v < field.height)) continue;
            row[x] = static_cast<float>(field.at(static_cast<int>(v), static_cast<int>(u))) * scale - 0.5f;
        }
    }
    return drawn;
}

// Those at least `margin` pixels inside the frame's border, where every
// shift looked at stays within it.
std::vector<DrawnEdge> drawn_edges(const std::vector<float>& drawn, int width, int height, int margin) {
    std::vector<DrawnEdge> edges;
    auto at = [&](int x, int y) { return drawn[static_cast<std::size_t>(y) * width + x]; };
    for (int y = margin; y + margin < height; ++y)
        for (int x = margin; x + margin < width; ++x) {
            // Only between two pixels on the field: its border is not an edge of its own.
            const float dx = at(x + 1, y) - at(x - 1, y), dy = at(x, y + 1) - at(x, y - 1);
            const float ex = std::isnan(dx) ? 0 : dx, ey = std::isnan(dy) ? 0 : dy;
            if (ex != 0 || ey != 0) edges.push_back({static_cast<std::ptrdiff_t>(y) * width + x, ex, ey});
        }
    return edges;
}

// The frame's differences across each pixel, both ways, clipped at a few
// times their median: the content's edges are tens of times the faint
// field's, and unclipped a few of them outweigh thousands of the field's.
struct ClippedGradients {
    int width = 0, height = 0;
    std::vector<float> dx, dy;
};

ClippedGradients clipped_gradients(const GreyView& frame, float clip_medians) {
    const int w = frame.width, h = frame.height;
    ClippedGradients g{w, h, std::vector<float>(static_cast<std::size_t>(w) * h, 0), {}};
    g.dy = g.dx;
    std::vector<float> sample;
    for (int y = 1; y + 1 < h; y += 3)
        for (int x = 1; x + 1 < w; x += 3) sample.push_back(std::abs(frame.at(x + 1, y) - frame.at(x - 1, y)));
    std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(sample.size() / 2), sample.end());
    const float clip = std::max(2.0f, clip_medians * sample[sample.size() / 2]);
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            g.dx[i] = std::clamp<float>(frame.at(x + 1, y) - frame.at(x - 1, y), -clip, clip);
            g.dy[i] = std::clamp<float>(frame.at(x, y + 1) - frame.at(x, y - 1), -clip, clip);
        }
    return g;
}

// The drawn edges' correlation with the frame's at a shift, over its own
// spread: the sum of the products over the square root of their squares.
double shifted_t(const std::vector<DrawnEdge>& edges, const ClippedGradients& g, int sx, int sy) {
    const std::ptrdiff_t shift = static_cast<std::ptrdiff_t>(sy) * g.width + sx;
    const float* dx = g.dx.data() + shift;
    const float* dy = g.dy.data() + shift;
    // Four sums side by side: one would wait on each addition before the next.
    float sum[4] = {0, 0, 0, 0}, squares[4] = {0, 0, 0, 0};
    const std::size_t n = edges.size();
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4)
        for (std::size_t k = 0; k < 4; ++k) {
            const DrawnEdge& e = edges[i + k];
            const float product = e.dx * dx[e.at] + e.dy * dy[e.at];
            sum[k] += product;
            squares[k] += product * product;
        }
    for (; i < n; ++i) {
        const float product = edges[i].dx * dx[edges[i].at] + edges[i].dy * dy[edges[i].at];
        sum[0] += product;
        squares[0] += product * product;
    }
    const double total = static_cast<double>(sum[0]) + sum[1] + sum[2] + sum[3];
    const double spread = static_cast<double>(squares[0]) + squares[1] + squares[2] + squares[3];
    return spread > 0 ? total / std::sqrt(spread) : 0;
}

// A module's side (pixels) at an image point under the map.
double module_px_at(const Eigen::Matrix3d& image_to_field, const Eigen::Vector2d& at) {
    const std::optional<Eigen::Matrix2d> d = homography_derivative(image_to_field, at);
    const double det = d ? std::abs(d->determinant()) : 0;
    return det > 0 && std::isfinite(det) ? 1 / std::sqrt(det) : 0;
}

// The peak of a parabola through three values, from the middle one (-0.5..0.5).
double vertex(double before, double at, double after) {
    const double curve = before - 2 * at + after;
    return curve < 0 ? std::clamp(0.5 * (before - after) / curve, -0.5, 0.5) : 0.0;
}

}  // namespace

FieldShift field_shift(const GreyView& frame, const Field& field, const Eigen::Matrix3d& image_to_field,
                       const FieldShiftOptions& options) {
    FieldShift out;
    const int w = frame.width, h = frame.height;
    if (!frame.data || w < 3 || h < 3 || field.modules.empty()) return out;
    out.module_px = module_px_at(image_to_field, {w / 2.0, h / 2.0});
    if (!(out.module_px > 0)) return out;
    const int reach =
        std::clamp(static_cast<int>(std::ceil(options.reach_modules * out.module_px)), 1, options.max_reach_px);
    const std::vector<DrawnEdge> edges = drawn_edges(drawn_field(field, image_to_field, w, h), w, h, reach + 1);
    out.edge_pixels = static_cast<int>(edges.size());
    // Too few edges to sum over: a handful of content edges would decide.
    constexpr int kMinEdgePixels = 500;
    if (out.edge_pixels < kMinEdgePixels) return out;
    const ClippedGradients gradients = clipped_gradients(frame, options.clip_medians);
    // Shifts a quarter of a module apart first, then pixel by pixel around the best of them.
    const int step = std::clamp(static_cast<int>(std::lround(out.module_px / 4)), 1, reach);
    const int side = 2 * reach + 1;
    std::vector<double> t(static_cast<std::size_t>(side) * side, std::nan(""));
    auto t_at = [&](int sx, int sy) {
        double& v = t[static_cast<std::size_t>(sy + reach) * side + sx + reach];
        if (std::isnan(v)) v = shifted_t(edges, gradients, sx, sy);
        return v;
    };
    int bx = 0, by = 0;
    for (int sy = -(reach / step) * step; sy <= reach; sy += step)
        for (int sx = -(reach / step) * step; sx <= reach; sx += step)
            if (t_at(sx, sy) > t_at(bx, by)) bx = sx, by = sy;
    // Uphill a pixel at a time from there.
    for (bool moved = step > 1; moved;) {
        moved = false;
        const int cx = bx, cy = by;
        for (int sy = std::max(-reach, cy - 1); sy <= std::min(reach, cy + 1); ++sy)
            for (int sx = std::max(-reach, cx - 1); sx <= std::min(reach, cx + 1); ++sx)
                if (t_at(sx, sy) > t_at(bx, by)) bx = sx, by = sy, moved = true;
    }
    // What the content alone gives: the same shifts of the field a few
    // modules along, which is another pattern of modules on the same grid.
    Eigen::Matrix3d along = Eigen::Matrix3d::Identity();
    along.topRightCorner<2, 1>() = Eigen::Vector2d(5, 2);
    const std::vector<DrawnEdge> other = drawn_edges(drawn_field(field, along * image_to_field, w, h), w, h, reach + 1);
    if (static_cast<int>(other.size()) >= kMinEdgePixels)
        for (int sy = -(reach / step) * step; sy <= reach; sy += step)
            for (int sx = -(reach / step) * step; sx <= reach; sx += step)
                out.content_t = std::max(out.content_t, shifted_t(other, gradients, sx, sy));
    out.measured = true;
    out.best_t = t_at(bx, by);
    out.place_t = t_at(0, 0);
    out.shift = Eigen::Vector2d(bx, by);
    if (std::abs(bx) < reach) out.shift.x() += vertex(t_at(bx - 1, by), out.best_t, t_at(bx + 1, by));
    if (std::abs(by) < reach) out.shift.y() += vertex(t_at(bx, by - 1), out.best_t, t_at(bx, by + 1));
    return out;
}

}  // namespace umf
