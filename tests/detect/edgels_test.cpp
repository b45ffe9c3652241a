#include "shared/detect/edgels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shared/field/field_io.hpp"

using namespace umf;

namespace {

// A field drawn with modules of `module_px` pixels, turned by `angle` about the
// image centre, at `contrast` grey levels around mid grey: a faint field on a
// blank screen, seen straight on.
struct Drawn {
    std::vector<std::uint8_t> pixels;
    int width, height;
    double module_px, angle;
};

Drawn draw_field(const Field& f, int width, int height, double module_px, double angle_deg, int contrast,
                 std::uint32_t noise_seed = 0, double noise_sigma = 0) {
    Drawn d{std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height), width, height, module_px,
            angle_deg * M_PI / 180};
    std::mt19937 rng(noise_seed);
    // A deviation must be positive even where no noise is drawn.
    std::normal_distribution<double> noise(0, noise_sigma > 0 ? noise_sigma : 1);
    const double c = std::cos(d.angle), s = std::sin(d.angle);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // 4 x 4 supersampling, as a camera integrates over a pixel.
            double acc = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const double px = x + (sx + 0.5) / 4 - width / 2.0, py = y + (sy + 0.5) / 4 - height / 2.0;
                    const double u = (c * px + s * py) / module_px + f.width / 2.0;
                    const double v = (-s * px + c * py) / module_px + f.height / 2.0;
                    const int col = static_cast<int>(std::floor(u)), row = static_cast<int>(std::floor(v));
                    double value = 128;
                    if (col >= 0 && row >= 0 && col < f.width && row < f.height)
                        value += contrast * (f.at(row, col) / double(f.colors - 1) - 0.5);
                    acc += value;
                }
            const double v = acc / 16 + (noise_sigma > 0 ? noise(rng) : 0);
            d.pixels[static_cast<std::size_t>(y) * width + x] = static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0));
        }
    return d;
}

// Distance in pixels from an image point to the nearest module boundary, and
// the angle between the edgel's gradient and that boundary's normal.
void boundary_fit(const Drawn& d, const Field& f, const Edgel& e, double& distance, double& angle_err_deg) {
    const double c = std::cos(d.angle), s = std::sin(d.angle);
    const double px = e.x - d.width / 2.0, py = e.y - d.height / 2.0;
    const double u = (c * px + s * py) / d.module_px + f.width / 2.0;
    const double v = (-s * px + c * py) / d.module_px + f.height / 2.0;
    const double du = std::abs(u - std::round(u)), dv = std::abs(v - std::round(v));
    // Gradient in field axes.
    const double gu = c * e.gx + s * e.gy, gv = -s * e.gx + c * e.gy;
    const double g = std::hypot(gu, gv);
    if (du < dv) {
        distance = du * d.module_px;
        angle_err_deg = std::acos(std::min(1.0, std::abs(gu) / g)) * 180 / M_PI;
    } else {
        distance = dv * d.module_px;
        angle_err_deg = std::acos(std::min(1.0, std::abs(gv) / g)) * 180 / M_PI;
    }
}

class EdgelsOnAField : public ::testing::TestWithParam<double> {};

TEST_P(EdgelsOnAField, LieOnModuleBoundariesAcrossThem) {
    Field f = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    Drawn d = draw_field(f, 640, 480, 28.0, GetParam(), 60, 1, 2.0);
    GreyView view{d.pixels.data(), d.width, d.height, d.width};
    EdgelScan scan = find_edgels(view);
    ASSERT_GT(scan.edgels.size(), 200u);
    int near = 0, across = 0;
    for (const auto& e : scan.edgels) {
        double dist, ang;
        boundary_fit(d, f, e, dist, ang);
        near += dist < 1.0;
        across += dist < 1.0 && ang < 15;
    }
    std::printf("angle %.0f: %zu edgels, %.1f %% within 1 px, %.1f %% also across\n", GetParam(), scan.edgels.size(),
                100.0 * near / scan.edgels.size(), 100.0 * across / scan.edgels.size());
    EXPECT_GT(near, static_cast<int>(0.95 * scan.edgels.size())) << "angle " << GetParam();
    EXPECT_GT(across, static_cast<int>(0.85 * scan.edgels.size())) << "angle " << GetParam();
    // Sparse: only the scanlines and a Sobel per edgel are read.
    EXPECT_LT(scan.pixels_visited, 0.2 * d.width * d.height);
}

INSTANTIATE_TEST_SUITE_P(Angles, EdgelsOnAField, ::testing::Values(0.0, 17.0, 45.0, 71.0, 133.0));

// A faint field in strong noise (a dim room): a lower bar finds more of its
// edges while the noise's own peaks stay a minority.
TEST(Edgels, ALowerBarFindsMoreOfAFaintFieldInNoise) {
    Field f = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    Drawn d = draw_field(f, 640, 480, 20.0, 17.0, 14, 3, 5.0);
    GreyView view{d.pixels.data(), d.width, d.height, d.width};
    auto on_boundaries = [&](double deviations, int& all) {
        EdgelOptions o;
        o.across = 3;
        o.noise_deviations = deviations;
        const EdgelScan scan = find_edgels(view, o);
        all = static_cast<int>(scan.edgels.size());
        int near = 0;
        for (const auto& e : scan.edgels) {
            double dist, ang;
            boundary_fit(d, f, e, dist, ang);
            near += dist < 1.0;
        }
        return near;
    };
    int all_strict = 0, all_lower = 0;
    const int strict = on_boundaries(4.5, all_strict), lower = on_boundaries(3, all_lower);
    std::printf("4.5 deviations: %d of %d edgels on boundaries; 3: %d of %d\n", strict, all_strict, lower, all_lower);
    // Measured: 339 of 340 at 4.5 deviations, 870 of 912 at 3.
    EXPECT_GT(lower, 2 * strict);
    EXPECT_GT(lower, all_lower * 17 / 20);
}

TEST(Edgels, FlatAndTinyImagesGiveNone) {
    std::vector<std::uint8_t> flat(100 * 80, 90);
    EXPECT_TRUE(find_edgels(GreyView{flat.data(), 100, 80, 100}).edgels.empty());
    EXPECT_TRUE(find_edgels(GreyView{flat.data(), 1, 1, 1}).edgels.empty());
    EXPECT_TRUE(find_edgels(GreyView{nullptr, 100, 80, 100}).edgels.empty());
    EXPECT_TRUE(find_edgels(GreyView{flat.data(), 100, 80, 50}).edgels.empty());  // stride below width
}

TEST(Edgels, HonourTheStride) {
    Field f = load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json");
    Drawn d = draw_field(f, 160, 120, 10.0, 20.0, 80);
    std::vector<std::uint8_t> padded(static_cast<std::size_t>(200) * 120, 0);
    for (int y = 0; y < 120; ++y)
        std::copy(d.pixels.begin() + y * 160, d.pixels.begin() + (y + 1) * 160, padded.begin() + y * 200);
    auto a = find_edgels(GreyView{d.pixels.data(), 160, 120, 160});
    auto b = find_edgels(GreyView{padded.data(), 160, 120, 200});
    ASSERT_EQ(a.edgels.size(), b.edgels.size());
    for (std::size_t i = 0; i < a.edgels.size(); ++i) EXPECT_EQ(a.edgels[i].x, b.edgels[i].x);
}

TEST(BringIntoCache, ReadsOnlyTheViewsRowsWhateverTheirWidthAndStride) {
    // Each view ends at the buffer's last byte (its last row without the
    // stride's padding): a read past the view is a read past the buffer,
    // which the sanitizer build stops. Widths about a cache line of 64
    // bytes, and the smallest views.
    for (const int width : {1, 63, 64, 65, 130}) {
        for (const int stride : {width, width + 7}) {
            const int height = 3;
            std::vector<std::uint8_t> pixels(static_cast<std::size_t>(stride) * (height - 1) + width, 7);
            const std::vector<std::uint8_t> before = pixels;
            bring_into_cache(GreyView{pixels.data(), width, height, stride});
            EXPECT_EQ(pixels, before) << width << " wide, stride " << stride;
        }
    }
}

TEST(Luma, WeighsChannelsInEveryOrder) {
    const std::uint8_t rgb[3] = {200, 100, 50}, bgr[3] = {50, 100, 200}, rgba[4] = {200, 100, 50, 255},
                       bgra[4] = {50, 100, 200, 0};
    std::vector<std::uint8_t> out;
    const int expected = (77 * 200 + 150 * 100 + 29 * 50 + 128) >> 8;
    EXPECT_EQ(to_luma({rgb, 1, 1, 3, PixelOrder::rgb}, out).at(0, 0), expected);
    EXPECT_EQ(to_luma({bgr, 1, 1, 3, PixelOrder::bgr}, out).at(0, 0), expected);
    EXPECT_EQ(to_luma({rgba, 1, 1, 4, PixelOrder::rgba}, out).at(0, 0), expected);
    EXPECT_EQ(to_luma({bgra, 1, 1, 4, PixelOrder::bgra}, out).at(0, 0), expected);
    EXPECT_THROW(to_luma({rgb, 1, 1, 2, PixelOrder::rgb}, out), std::invalid_argument);
}

TEST(HalfSize, AveragesTwoByTwoBlocksAndDropsAnOddLastRowAndColumn) {
    // 5 x 3 with a stride of 6: the sixth byte of a row and the last row
    // and column are not read.
    const std::uint8_t pixels[18] = {0,  10, 100, 101, 9, 77,  //
                                     20, 31, 102, 104, 9, 77,  //
                                     99, 99, 99,  99,  9, 77};
    std::vector<std::uint8_t> out;
    const GreyView half = half_size({pixels, 5, 3, 6}, out);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_EQ(half.stride, 2);
    EXPECT_EQ(half.at(0, 0), 15);   // (0 + 10 + 20 + 31 + 2) / 4
    EXPECT_EQ(half.at(1, 0), 102);  // (100 + 101 + 102 + 104 + 2) / 4
}

TEST(Smoothed, FlattensAFineHatchAndKeepsAStepWhole) {
    // 24 x 12 with a stride of 26: a hatch of 2 px (columns 0 and 255 by
    // turns), and a step at x = 12 from 40 to 200.
    std::vector<std::uint8_t> hatch(26 * 12, 255), step(26 * 12, 255);
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 24; ++x) {
            hatch[26 * y + x] = x % 2 ? 255 : 0;
            step[26 * y + x] = x < 12 ? 40 : 200;
        }
    std::vector<std::uint8_t> out;
    const GreyView flat = smoothed({hatch.data(), 24, 12, 26}, out);
    ASSERT_EQ(flat.width, 24);
    ASSERT_EQ(flat.height, 12);
    EXPECT_EQ(flat.stride, 24);
    // (1 8 28 56 70 56 28 8 1) / 256 sums to 128 over either parity.
    for (int y = 0; y < 12; ++y)
        for (int x = 4; x < 20; ++x) EXPECT_NEAR(flat.at(x, y), 127.5, 0.5) << x << ", " << y;
    const GreyView edge = smoothed({step.data(), 24, 12, 26}, out);
    for (int y = 0; y < 12; ++y) {
        // Symmetric about the middle grey between pixels 11 and 12, whole
        // four pixels away (the border repeats the edge pixels).
        for (int d = 0; d < 6; ++d) EXPECT_NEAR(edge.at(11 - d, y) + edge.at(12 + d, y), 240, 1) << d;
        EXPECT_LT(edge.at(11, y), 120);
        EXPECT_GT(edge.at(12, y), 120);
        EXPECT_EQ(edge.at(0, y), 40);
        EXPECT_EQ(edge.at(23, y), 200);
    }
}

TEST(DoubleSize, KeepsARampAndPutsAStepAtTwiceItsPlace) {
    // 10 x 3 with a stride of 12; every row a ramp 10, 30, ..., 190 (pixel i
    // centred at i + 0.5 has 20 i + 10), or every row a step at x = 5.
    std::vector<std::uint8_t> ramp(36, 255), step(36, 255);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 10; ++x) {
            ramp[12 * y + x] = static_cast<std::uint8_t>(20 * x + 10);
            step[12 * y + x] = x < 5 ? 40 : 200;
        }
    std::vector<std::uint8_t> out;
    const GreyView twice = double_size({ramp.data(), 10, 3, 12}, out);
    ASSERT_EQ(twice.width, 20);
    ASSERT_EQ(twice.height, 6);
    EXPECT_EQ(twice.stride, 20);
    // Pixel j of the doubled ramp is centred at (j + 0.5) / 2 of the
    // original: 10 j + 5 away from the ends (Keys' cubic with a = -0.75
    // sharpens a little: within a grey level on this ramp).
    for (int y = 0; y < 6; ++y)
        for (int j = 4; j < 16; ++j) EXPECT_NEAR(twice.at(j, y), 10 * j + 5, 1) << j << ", " << y;
    // The step's edge lands at x = 10, between pixels 9 and 10, symmetric
    // about the middle grey; the cubic overshoots a little on either side.
    const GreyView edge = double_size({step.data(), 10, 3, 12}, out);
    for (int y = 0; y < 6; ++y) {
        EXPECT_NEAR(edge.at(9, y) + edge.at(10, y), 240, 1);
        EXPECT_NEAR(edge.at(8, y) + edge.at(11, y), 240, 1);
        EXPECT_LT(edge.at(8, y), edge.at(9, y));
        EXPECT_LT(edge.at(9, y), 120);
        EXPECT_GT(edge.at(10, y), 120);
        EXPECT_EQ(edge.at(0, y), 40);
        EXPECT_EQ(edge.at(19, y), 200);
    }
}

}  // namespace
