// The lattice read from the spectrum of edge strength: on a field of small
// modules turned and sheared, its lines fall on the module edges; on a patch
// without a grid there is none.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "shared/detect/lattice.hpp"

namespace {

using namespace umf;

struct Rendered {
    std::vector<std::uint8_t> pixels;
    GreyView view;
    Eigen::Matrix2d image_to_module;  // about the origin
};

// Random binary modules (grey 90 and 150), drawn through an affine map from
// module coordinates to the image, 4 x 4 samples a pixel; pixel (x, y)
// covers [x, x + 1) x [y, y + 1), as the detector reads it.
Rendered render(double module_px, double turn_deg, double shear, int w, int h, std::uint32_t seed) {
    Rendered r;
    const double a = turn_deg * M_PI / 180;
    Eigen::Matrix2d m2i;
    m2i << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    Eigen::Matrix2d s;
    s << 1, shear, 0, 1;
    m2i = module_px * m2i * s;
    r.image_to_module = m2i.inverse();
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> bits(400 * 400);
    for (auto& b : bits) b = static_cast<std::uint8_t>(rng() & 1);
    r.pixels.resize(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const Eigen::Vector2d m = r.image_to_module * Eigen::Vector2d(x + (sx + 0.5) / 4, y + (sy + 0.5) / 4);
                    const int i = static_cast<int>(std::floor(m.x())) + 200, j = static_cast<int>(std::floor(m.y())) + 200;
                    sum += bits[static_cast<std::size_t>(j) * 400 + static_cast<std::size_t>(i)] ? 150 : 90;
                }
            r.pixels[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint8_t>(std::lround(sum / 16));
        }
    r.view = {r.pixels.data(), w, h, w};
    return r;
}

// How far (modules) the lattice's cell corners lie from the field's module
// corners, at most, over the patch.
double worst_corner_miss(const Lattice& l, const Eigen::Matrix2d& image_to_module) {
    double worst = 0;
    for (int y = 0; y <= l.rows; ++y)
        for (int x = 0; x <= l.cols; ++x) {
            const Eigen::Vector3d p = l.grid_to_image * Eigen::Vector3d(x, y, 1);
            const Eigen::Vector2d m = image_to_module * p.hnormalized();
            if (p.x() < 0 || p.y() < 0 || p.x() > 319 || p.y() > 239) continue;
            worst = std::max({worst, std::abs(m.x() - std::round(m.x())), std::abs(m.y() - std::round(m.y()))});
        }
    return worst;
}

TEST(Lattice, ItsLinesFallOnTheEdgesOfSmallTurnedModules) {
    for (const auto& [module, turn, shear] : {std::tuple{3.5, 20.0, 0.0}, {4.0, 63.0, 0.15}, {6.0, -35.0, -0.1}}) {
        const Rendered r = render(module, turn, shear, 320, 240, 7);
        const auto lattices = find_lattices(r.view, {160, 120});
        ASSERT_FALSE(lattices.empty()) << module << " px at " << turn << " degrees";
        const Lattice& l = lattices.front();
        EXPECT_GT(l.rows, 20 * 4 / module);
        EXPECT_GT(l.cols, 20 * 4 / module);
        // The grid's turn never mirrors the image.
        const Eigen::Matrix2d linear = l.grid_to_image.topLeftCorner(2, 2);
        EXPECT_GT(linear.determinant(), 0);
        EXPECT_LT(worst_corner_miss(l, r.image_to_module), 0.06) << module << " px at " << turn << " degrees";
    }
}

TEST(Lattice, NoneOnAFlatOrNoisyPatchOrASmallImage) {
    std::vector<std::uint8_t> flat(320 * 240, 128);
    EXPECT_TRUE(find_lattices({flat.data(), 320, 240, 320}, {160, 120}).empty());
    std::mt19937 rng(5);
    std::vector<std::uint8_t> noise(320 * 240);
    for (auto& p : noise) p = static_cast<std::uint8_t>(100 + rng() % 40);
    EXPECT_TRUE(find_lattices({noise.data(), 320, 240, 320}, {160, 120}).empty());
    const Rendered small = render(4, 10, 0, 100, 100, 3);
    EXPECT_TRUE(find_lattices(small.view, {50, 50}).empty());
}

}  // namespace
