// The field's own edges among all edgels: its steps are alike, so the
// commonest step is the field's, and only edgels near it are kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "shared/detect/edgels.hpp"
#include "shared/detect/field_edgels.hpp"
#include "shared/detect/image.hpp"

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

// A spreadsheet's rule crosses a scanline as a dark line: a falling edge
// and a rising one, two to four pixels apart, of like step. Such pairs go;
// the field's edges, a module apart, stay, and so do a step next to a far
// stronger one and two edges of the same sign.
TEST(FieldEdgels, ThinLinesLeaveTheFieldsEdges) {
    const int w = 200, h = 40;
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h, 200);
    for (int y = 0; y < h; ++y) {
        std::uint8_t* row = pixels.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            int v = 200;
            if ((x / 20) % 2 == 1) v -= 25;  // the field's modules, 20 px
            if (x % 60 == 47 || x % 60 == 48) v -= 60;  // a rule 2 px wide inside a module
            row[x] = static_cast<std::uint8_t>(v);
        }
    }
    const EdgelScan scan = find_edgels(GreyView{pixels.data(), w, h, w}, EdgelOptions{10, 5, 5});
    const std::vector<Edgel> kept = edgels_off_thin_lines(scan.edgels, 6);
    auto on_field = [](const Edgel& e) {
        const float m = std::fmod(e.x, 20.0f);
        return m < 1.5f || m > 18.5f;
    };
    int field = 0, rule = 0;
    for (const Edgel& e : scan.edgels) {
        field += on_field(e);
        rule += !on_field(e);
    }
    ASSERT_GT(field, 0);
    ASSERT_GT(rule, 0) << "the rules give edgels of their own";
    int field_kept = 0, rule_kept = 0;
    for (const Edgel& e : kept) {
        field_kept += on_field(e);
        rule_kept += !on_field(e);
    }
    EXPECT_EQ(field_kept, field) << "every field edge kept";
    EXPECT_EQ(rule_kept, 0) << "every rule's edge left out";

    // Two edges of the same sign close together, or of unlike steps, are not a line.
    Edgel a, b;
    a.x = 10, b.x = 13, a.y = b.y = 5, a.gx = 50, b.gx = 40, a.step = 20, b.step = 18;
    EXPECT_EQ(edgels_off_thin_lines({a, b}, 6).size(), 2u);
    b.gx = -40;
    EXPECT_EQ(edgels_off_thin_lines({a, b}, 6).size(), 0u);
    b.step = 60;
    EXPECT_EQ(edgels_off_thin_lines({a, b}, 6).size(), 2u);
    b.step = 18, b.x = 20;
    EXPECT_EQ(edgels_off_thin_lines({a, b}, 6).size(), 2u) << "a module apart";
}

// Edgels of one step on `rows` row scanlines, `gap_px` apart along each.
std::vector<Edgel> edges_every(float gap_px, int rows, int per_row, float step = 20) {
    std::vector<Edgel> out;
    for (int r = 0; r < rows; ++r)
        for (int k = 0; k < per_row; ++k) {
            Edgel e = with_step(step);
            e.y = static_cast<float>(8 * r + 4);
            e.x = 2.3f + gap_px * static_cast<float>(k);
            out.push_back(e);
        }
    return out;
}

TEST(FieldEdgels, ModulesLookSmallWhenTheFieldsEdgesLieAFewPixelsApart) {
    EXPECT_TRUE(modules_look_small(edges_every(4, 10, 30))) << "a far field's modules, 4 px";
    EXPECT_TRUE(modules_look_small(edges_every(5, 10, 30)));
    EXPECT_FALSE(modules_look_small(edges_every(6, 10, 30)));
    EXPECT_FALSE(modules_look_small(edges_every(12, 10, 30))) << "modules of 12 px";
    EXPECT_FALSE(modules_look_small(edges_every(4, 3, 30))) << "87 gaps, too few to say";
    // Text's strong edges close together do not count: only the edgels of the
    // commonest step (the field's, 12 px apart here) are measured.
    std::vector<Edgel> both = edges_every(12, 10, 30);
    const std::vector<Edgel> text = edges_every(3, 6, 40, 120);
    both.insert(both.end(), text.begin(), text.end());
    EXPECT_FALSE(modules_look_small(both));
    // Gaps are measured along each scanline, never from one to the next.
    std::vector<Edgel> one_a_row = edges_every(4, 200, 1);
    EXPECT_FALSE(modules_look_small(one_a_row));
}

}  // namespace
}  // namespace umf
