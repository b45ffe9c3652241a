#include "shared/detect/field_shift.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cstdint>
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

// The field's modules where a map puts them, a module's colour a pixel; -1
// off the field. A field of more colours is not drawn.
constexpr int kMostColours = 127;
struct DrawnField {
    int width = 0, height = 0;
    std::vector<std::int8_t> colour;
};

// The modules where `image_to_field` puts them (`place`) and the same map's
// modules `along` further on (`other`): one pass of the map over the frame
// draws both, the costly part being the map's division at each pixel.
void draw_fields(const Field& field, const Eigen::Matrix3d& image_to_field, const Eigen::Vector2i& along, int width,
                 int height, DrawnField& place, DrawnField& other) {
    for (DrawnField* d : {&place, &other}) {
        d->width = width;
        d->height = height;
        d->colour.assign(static_cast<std::size_t>(width) * height, -1);
    }
    // The view's side of the horizon: that of the frame's centre.
    const double front = (image_to_field * Eigen::Vector3d(width / 2.0, height / 2.0, 1)).z();
    const Eigen::Vector3d step = image_to_field.col(0);
    auto inside = [&](int u, int v) { return u >= 0 && v >= 0 && u < field.width && v < field.height; };
    for (int y = 0; y < height; ++y) {
        Eigen::Vector3d p = image_to_field * Eigen::Vector3d(0, y, 1);
        std::int8_t* row = place.colour.data() + static_cast<std::size_t>(y) * width;
        std::int8_t* other_row = other.colour.data() + static_cast<std::size_t>(y) * width;
        for (int x = 0; x < width; ++x, p += step) {
            if (p.z() * front <= 0) continue;
            const double u = p.x() / p.z(), v = p.y() / p.z();
            // Where either is on the field (`along` goes up the field's axes).
            if (!(u >= -along.x() && v >= -along.y() && u < field.width && v < field.height)) continue;
            const int iu = static_cast<int>(std::floor(u)), iv = static_cast<int>(std::floor(v));
            if (inside(iu, iv)) row[x] = static_cast<std::int8_t>(field.at(iv, iu));
            if (inside(iu + along.x(), iv + along.y()))
                other_row[x] = static_cast<std::int8_t>(field.at(iv + along.y(), iu + along.x()));
        }
    }
}

// Its edges at least `margin` pixels inside the frame's border, where every
// shift looked at stays within it.
std::vector<DrawnEdge> drawn_edges(const DrawnField& drawn, int colors, int margin) {
    const int width = drawn.width, height = drawn.height;
    // A colour's share of the field's range, from -0.5 (its first colour) to 0.5 (its last).
    const float scale = colors > 1 ? 1.0f / static_cast<float>(colors - 1) : 0.0f;
    std::array<float, kMostColours> level{};
    for (int c = 0; c < colors && c < kMostColours; ++c)
        level[static_cast<std::size_t>(c)] = static_cast<float>(c) * scale - 0.5f;
    // Only between two pixels on the field: its border is not an edge of its own.
    auto change = [&](std::int8_t from, std::int8_t to) {
        if (from < 0 || to < 0) return 0.0f;
        return level[static_cast<std::size_t>(to)] - level[static_cast<std::size_t>(from)];
    };
    std::vector<DrawnEdge> edges;
    edges.reserve(static_cast<std::size_t>(width) * height / 4);
    for (int y = margin; y + margin < height; ++y) {
        const std::int8_t* row = drawn.colour.data() + static_cast<std::size_t>(y) * width;
        const std::int8_t *above = row - width, *below = row + width;
        for (int x = margin; x + margin < width; ++x) {
            // Most pixels lie inside a module: the same colour all round.
            if (row[x - 1] == row[x + 1] && above[x] == below[x]) continue;
            const float dx = change(row[x - 1], row[x + 1]), dy = change(above[x], below[x]);
            if (dx != 0 || dy != 0) edges.push_back({static_cast<std::ptrdiff_t>(y) * width + x, dx, dy});
        }
    }
    return edges;
}

// The frame's differences across each pixel, both ways, clipped at a few
// times their median: the content's edges are tens of times the faint
// field's, and unclipped a few of them outweigh thousands of the field's.
// Both of a pixel side by side, so that a shift's sum reads each edge
// pixel's pair at once; whole grey levels, and the clip is whole too.
struct ClippedGradients {
    int width = 0;
    std::vector<std::array<std::int16_t, 2>> d;  // x, y
};

ClippedGradients clipped_gradients(const GreyView& frame, float clip_medians) {
    const int w = frame.width, h = frame.height;
    ClippedGradients g{w, std::vector<std::array<std::int16_t, 2>>(static_cast<std::size_t>(w) * h, {0, 0})};
    std::vector<int> sample;
    for (int y = 1; y + 1 < h; y += 3)
        for (int x = 1; x + 1 < w; x += 3) sample.push_back(std::abs(frame.at(x + 1, y) - frame.at(x - 1, y)));
    std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(sample.size() / 2), sample.end());
    const float median = static_cast<float>(sample[sample.size() / 2]);
    const int clip = std::max(2, static_cast<int>(std::floor(clip_medians * median)));
    for (int y = 1; y + 1 < h; ++y) {
        const std::uint8_t *row = frame.row(y), *above = frame.row(y - 1), *below = frame.row(y + 1);
        std::array<std::int16_t, 2>* out = g.d.data() + static_cast<std::size_t>(y) * w;
        for (int x = 1; x + 1 < w; ++x)
            out[x] = {static_cast<std::int16_t>(std::clamp(row[x + 1] - row[x - 1], -clip, clip)),
                      static_cast<std::int16_t>(std::clamp(below[x] - above[x], -clip, clip))};
    }
    return g;
}

// The drawn edges' correlation with the frame's at a shift, over its own
// spread: the sum of the products over the square root of their squares.
double shifted_t(const std::vector<DrawnEdge>& edges, const ClippedGradients& g, int sx, int sy) {
    const std::array<std::int16_t, 2>* d = g.d.data() + static_cast<std::ptrdiff_t>(sy) * g.width + sx;
    // Four sums side by side: one would wait on each addition before the next.
    float sum[4] = {0, 0, 0, 0}, squares[4] = {0, 0, 0, 0};
    const std::size_t n = edges.size();
    std::size_t i = 0;
    auto product = [&](const DrawnEdge& e) {
        const std::array<std::int16_t, 2>& here = d[e.at];
        return e.dx * static_cast<float>(here[0]) + e.dy * static_cast<float>(here[1]);
    };
    for (; i + 4 <= n; i += 4)
        for (std::size_t k = 0; k < 4; ++k) {
            const float p = product(edges[i + k]);
            sum[k] += p;
            squares[k] += p * p;
        }
    for (; i < n; ++i) {
        const float p = product(edges[i]);
        sum[0] += p;
        squares[0] += p * p;
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
    if (!frame.data || w < 3 || h < 3 || field.modules.empty() || field.colors > kMostColours) return out;
    out.module_px = module_px_at(image_to_field, {w / 2.0, h / 2.0});
    if (!(out.module_px > 0)) return out;
    const int reach =
        std::clamp(static_cast<int>(std::ceil(options.reach_modules * out.module_px)), 1, options.max_reach_px);
    // What the content alone gives: the same shifts of the field a few
    // modules along, which is another pattern of modules on the same grid.
    DrawnField place, other;
    draw_fields(field, image_to_field, Eigen::Vector2i(5, 2), w, h, place, other);
    const std::vector<DrawnEdge> edges = drawn_edges(place, field.colors, reach + 1);
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
    const std::vector<DrawnEdge> other_edges = drawn_edges(other, field.colors, reach + 1);
    if (static_cast<int>(other_edges.size()) >= kMinEdgePixels)
        for (int sy = -(reach / step) * step; sy <= reach; sy += step)
            for (int sx = -(reach / step) * step; sx <= reach; sx += step)
                out.content_t = std::max(out.content_t, shifted_t(other_edges, gradients, sx, sy));
    out.measured = true;
    out.best_t = t_at(bx, by);
    out.place_t = t_at(0, 0);
    out.shift = Eigen::Vector2d(bx, by);
    if (std::abs(bx) < reach) out.shift.x() += vertex(t_at(bx - 1, by), out.best_t, t_at(bx + 1, by));
    if (std::abs(by) < reach) out.shift.y() += vertex(t_at(bx, by - 1), out.best_t, t_at(bx, by + 1));
    return out;
}

}  // namespace umf
