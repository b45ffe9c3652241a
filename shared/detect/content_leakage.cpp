#include "shared/detect/content_leakage.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace umf {

namespace {

std::size_t at(int x, int y, int width) { return static_cast<std::size_t>(y) * width + x; }

// The Laplacian (4-neighbour) of a plane, and its central gradients where asked.
struct Derivatives {
    std::vector<float> dx, dy, laplacian;
};

Derivatives derivatives(const std::vector<float>& p, int width, int height, bool gradients) {
    Derivatives d;
    d.laplacian.resize(p.size());
    if (gradients) {
        d.dx.resize(p.size());
        d.dy.resize(p.size());
    }
    for (int y = 0; y < height; ++y) {
        const int up = std::max(0, y - 1), down = std::min(height - 1, y + 1);
        for (int x = 0; x < width; ++x) {
            const int left = std::max(0, x - 1), right = std::min(width - 1, x + 1);
            const float c = p[at(x, y, width)], l = p[at(left, y, width)], r = p[at(right, y, width)];
            const float u = p[at(x, up, width)], w = p[at(x, down, width)];
            d.laplacian[at(x, y, width)] = l + r + u + w - 4 * c;
            if (!gradients) continue;
            d.dx[at(x, y, width)] = (r - l) / 2;
            d.dy[at(x, y, width)] = (w - u) / 2;
        }
    }
    return d;
}

}  // namespace

std::vector<float> gaussian_blurred(const std::vector<float>& plane, int width, int height, double sigma) {
    const int radius = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
    std::vector<float> kernel(static_cast<std::size_t>(2 * radius + 1));
    float total = 0;
    for (int i = -radius; i <= radius; ++i)
        total += kernel[static_cast<std::size_t>(i + radius)] =
            static_cast<float>(std::exp(-i * i / (2 * sigma * sigma)));
    for (float& k : kernel) k /= total;
    const float* weight = kernel.data() + radius;  // weight[i] for i in -radius..radius
    std::vector<float> across(plane.size()), out(plane.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float sum = 0;
            for (int i = -radius; i <= radius; ++i)
                sum += weight[i] * plane[at(std::clamp(x + i, 0, width - 1), y, width)];
            across[at(x, y, width)] = sum;
        }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float sum = 0;
            for (int i = -radius; i <= radius; ++i)
                sum += weight[i] * across[at(x, std::clamp(y + i, 0, height - 1), width)];
            out[at(x, y, width)] = sum;
        }
    return out;
}

void remove_content_leakage(std::vector<float>& slope, const std::vector<float>& mean, int width, int height,
                            int tile) {
    const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (width <= 0 || height <= 0 || slope.size() != pixels || mean.size() != pixels)
        throw std::invalid_argument("content leakage: the slope and the mean must be width x height planes");
    if (tile < 8) throw std::invalid_argument("content leakage: a tile must be at least 8 pixels a side");
    // The content changed a little: its level, a shift (the gradients), a
    // blur at the pixel's scale and one at a few pixels' (the Laplacians).
    const Derivatives fine = derivatives(gaussian_blurred(mean, width, height, 0.7), width, height, true);
    const std::vector<float> coarse =
        derivatives(gaussian_blurred(mean, width, height, 2.0), width, height, false).laplacian;
    const std::array<const std::vector<float>*, 5> basis = {&mean, &fine.dx, &fine.dy, &fine.laplacian, &coarse};
    constexpr int k = static_cast<int>(basis.size()) + 1;  // and a constant
    using Row = Eigen::Matrix<double, k, 1>;
    auto row_at = [&](std::size_t i) {
        Row r;
        r(0) = 1;
        for (int j = 0; j < k - 1; ++j) r(j + 1) = (*basis[static_cast<std::size_t>(j)])[i];
        return r;
    };
    for (int ty = 0; ty < height; ty += tile)
        for (int tx = 0; tx < width; tx += tile) {
            const int x_end = std::min(width, tx + tile), y_end = std::min(height, ty + tile);
            Eigen::Matrix<double, k, k> normal = Eigen::Matrix<double, k, k>::Zero();
            Row target = Row::Zero();
            for (int y = ty; y < y_end; ++y)
                for (int x = tx; x < x_end; ++x) {
                    const Row r = row_at(at(x, y, width));
                    normal.selfadjointView<Eigen::Lower>().rankUpdate(r);
                    target += r * slope[at(x, y, width)];
                }
            normal = normal.selfadjointView<Eigen::Lower>();
            // A little ridge: a flat tile's basis images are all but zero.
            const Row weights = (normal + 1e-6 * normal.diagonal().maxCoeff() * Eigen::Matrix<double, k, k>::Identity())
                                    .ldlt()
                                    .solve(target);
            for (int y = ty; y < y_end; ++y)
                for (int x = tx; x < x_end; ++x) {
                    const std::size_t i = at(x, y, width);
                    slope[i] -= static_cast<float>(weights.dot(row_at(i)));
                }
        }
}

}  // namespace umf
