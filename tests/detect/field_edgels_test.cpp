// The field's own edges among all edgels: its steps are alike, so the
// commonest step is the field's, and only edgels near it are kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "detect/edgels.hpp"
#include "detect/field_edgels.hpp"
#include "detect/image.hpp"

namespace umf {
namespace {

Edgel with_step(float step) {
    Edgel e;
    e.step = step;
    return e;
}

TEST(FieldEdgels, TheCommonestStepIsTheFaintFieldsUnderStrongerText) {
    std::vector<Edgel> edgels;
    // A faint field: 300 edges of 20-26 levels; text: 120 edges spread over 60-220.
    for (int i = 0; i < 300; ++i) edgels.push_back(with_step(20.0f + static_cast<float>(i % 7)));
    for (int i = 0; i < 120; ++i) edgels.push_back(with_step(60.0f + static_cast<float>(i * 4 % 160)));
    const double step = commonest_edge_step(edgels);
    EXPECT_GT(step, 17);
    EXPECT_LT(step, 30);
    const auto kept = edgels_stepping_by(edgels, step);
    int field = 0;
    for (const Edgel& e : kept) field += e.step < 30;
    EXPECT_EQ(field, 300) << "every field edge kept";
    EXPECT_LT(kept.size() - field, 25u) << "most text edges left out";
}

TEST(FieldEdgels, TooFewEdgelsSayNothing) {
    EXPECT_EQ(commonest_edge_step(std::vector<Edgel>(39, with_step(20))), 0);
    EXPECT_TRUE(edgels_stepping_by(std::vector<Edgel>(50, with_step(20)), 0).empty());
}

TEST(FieldEdgels, AnEdgelsStepIsTheLevelsAcrossIt) {
    // A vertical edge from 100 to 140 grey levels: the step is 40.
    const int w = 64, h = 64;
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) pixels[static_cast<std::size_t>(y) * w + x] = x < 30 ? 100 : 140;
    const EdgelScan scan = find_edgels(GreyView{pixels.data(), w, h, w}, EdgelOptions{8, 4, 5});
    ASSERT_FALSE(scan.edgels.empty());
    for (const Edgel& e : scan.edgels) EXPECT_NEAR(e.step, 40, 1) << "at " << e.x << "," << e.y;
}

// A faint, slightly blurred edge in strong noise: lost on single-pixel
// scanlines, held when three pixels across each line are read.
TEST(FieldEdgels, ReadingAcrossTheScanlineHoldsAFaintEdgeInNoise) {
    const int w = 96, h = 96;
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h);
    std::uint64_t state = 12345;
    auto gauss = [&] {  // a sum of uniforms, sigma 1
        double s = 0;
        for (int k = 0; k < 12; ++k) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            s += static_cast<double>(state >> 11) / 9007199254740992.0;
        }
        return s - 6;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double ramp = std::clamp((x - 47.0) / 3.0, 0.0, 1.0);  // a three-pixel transition
            pixels[static_cast<std::size_t>(y) * w + x] =
                static_cast<std::uint8_t>(std::clamp(40 + 22 * ramp + 6 * gauss(), 0.0, 255.0));
        }
    const GreyView view{pixels.data(), w, h, w};
    const auto on_the_edge = [](const EdgelScan& scan) {
        int n = 0;
        for (const Edgel& e : scan.edgels) n += e.on_row && std::abs(e.x - 49) < 2.5;
        return n;
    };
    EdgelOptions thin{8, 4, 5};
    EdgelOptions wide = thin;
    wide.across = 3;
    const EdgelScan one = find_edgels(view, thin), three = find_edgels(view, wide);
    // 12 rows are scanned; the noise's estimate stays a single pixel's either way.
    EXPECT_LE(on_the_edge(one), 6);
    EXPECT_GE(on_the_edge(three), 9);
    std::cout << "[ measure  ] edge found on " << on_the_edge(one) << " of 12 rows, " << on_the_edge(three) << " reading three pixels across\n";
    EXPECT_NEAR(one.noise_sigma, 6, 2);
    EXPECT_NEAR(three.noise_sigma, 6, 2);
}

}  // namespace
}  // namespace umf
