#include "shared/field/generator.hpp"

#include <gtest/gtest.h>

#include "shared/field/contrast.hpp"
#include "shared/field/verifier.hpp"
#include "tests/field/test_fields.hpp"

using namespace umf;

namespace {

GeneratorOptions options(int w, int h, int n, int k, std::uint64_t seed) {
    GeneratorOptions o;
    o.width = w;
    o.height = h;
    o.window = n;
    o.colors = k;
    o.key = default_key(k);
    o.seed = seed;
    return o;
}

void expect_valid(const GeneratorResult& r, const GeneratorOptions& o) {
    ASSERT_TRUE(r.complete);
    EXPECT_EQ(r.field.width, o.width);
    EXPECT_EQ(r.field.height, o.height);
    EXPECT_EQ(r.field.window, o.window);
    EXPECT_EQ(r.field.colors, o.colors);
    EXPECT_EQ(r.field.key, o.key);
    EXPECT_TRUE(describe_invalid(r.field).empty());
    auto report = verify_field(r.field);
    EXPECT_TRUE(report.orientable()) << report.conflicts.size() << " conflicts, first: "
                                     << (report.conflicts.empty() ? "" : describe(report.conflicts[0]));
}

struct Shape {
    int w, h, n, k;
    WindowKey key;
};

class GeneratorShapes : public ::testing::TestWithParam<Shape> {};

TEST_P(GeneratorShapes, OutputAlwaysVerifies) {
    auto s = GetParam();
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        auto o = options(s.w, s.h, s.n, s.k, seed);
        o.key = s.key;
        expect_valid(generate_field(o), o);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, GeneratorShapes,
    ::testing::Values(Shape{64, 36, 4, 2, WindowKey::modules}, Shape{36, 64, 4, 2, WindowKey::modules},
                      Shape{9, 9, 3, 2, WindowKey::modules}, Shape{4, 4, 4, 2, WindowKey::modules},
                      Shape{48, 27, 3, 3, WindowKey::edges}, Shape{64, 36, 3, 4, WindowKey::edges},
                      Shape{40, 30, 3, 5, WindowKey::edges}, Shape{64, 36, 4, 3, WindowKey::edges},
                      Shape{20, 20, 3, 3, WindowKey::modules}, Shape{150, 3, 3, 4, WindowKey::edges}),
    [](const ::testing::TestParamInfo<Shape>& info) {
        const auto& s = info.param;
        return std::to_string(s.w) + "x" + std::to_string(s.h) + "_n" + std::to_string(s.n) + "_k" +
               std::to_string(s.k) + "_" + to_string(s.key);
    });

TEST(Generator, IsReproducibleBySeed) {
    auto o = options(48, 27, 4, 2, 17);
    auto a = generate_field(o), b = generate_field(o);
    EXPECT_EQ(a.field.modules, b.field.modules);
    EXPECT_EQ(a.field.id, "b4-48x27-s17");
    o.seed = 18;
    EXPECT_NE(generate_field(o).field.modules, a.field.modules);
}

TEST(Generator, ResultDoesNotDependOnThreads) {
    auto o = options(80, 80, 4, 2, 5);
    o.chains = 3;
    o.threads = 1;
    auto one = generate_field(o);
    o.threads = 3;
    auto three = generate_field(o);
    EXPECT_EQ(one.field.modules, three.field.modules);
    EXPECT_EQ(one.winning_chain, three.winning_chain);
}

TEST(Generator, KaryFieldsHaveStrongerEdgesThanRandomOnes) {
    for (int n : {3, 4}) {
        auto o = options(64, 36, n, 4, 1);
        o.contrast_steps = 0;
        auto rough = generate_field(o);
        o.contrast_steps = -1;
        auto polished = generate_field(o);
        expect_valid(polished, o);
        auto random = edge_contrast(test::random_field(64, 36, n, 4, 1, WindowKey::edges));
        auto before = edge_contrast(rough.field), after = edge_contrast(polished.field);
        // 3 x 3 windows need flat edges as a third symbol to stay distinct; 4 x 4 windows do not.
        if (n == 4) {
            EXPECT_LT(after.flat_fraction(), random.flat_fraction() * 0.5);
        }
        EXPECT_LE(after.flat_fraction(), before.flat_fraction()) << "n=" << n;
        EXPECT_GT(after.mean_step, random.mean_step) << "n=" << n;
    }
}

TEST(Generator, RefusesImpossibleRequests) {
    EXPECT_THROW(generate_field(options(140, 140, 4, 2, 1)), std::invalid_argument);  // above the counting bound
    EXPECT_THROW(generate_field(options(13, 13, 3, 2, 1)), std::invalid_argument);
    EXPECT_THROW(generate_field(options(3, 10, 4, 2, 1)), std::invalid_argument);
    EXPECT_THROW(generate_field(options(10, 10, 5, 2, 1)), std::invalid_argument);
    EXPECT_THROW(generate_field(options(0, 10, 4, 2, 1)), std::invalid_argument);
    EXPECT_THROW(generate_field(options(10, 10, 3, 11, 1)), std::invalid_argument);
    auto o = options(10, 10, 4, 2, 1);
    o.chains = 0;
    EXPECT_THROW(generate_field(o), std::invalid_argument);
}

TEST(Generator, StopsOnRequestWithThePartialField) {
    auto o = options(125, 125, 4, 2, 1);  // far beyond what a fraction of a second can build
    std::atomic<bool> stop{true};
    int calls = 0;
    auto r = generate_field(o, [&](const GeneratorProgress& p) {
        ++calls;
        EXPECT_EQ(p.windows_total, 122L * 122);
        EXPECT_GT(p.windows_placed, 0);
    }, &stop);
    EXPECT_FALSE(r.complete);
    EXPECT_TRUE(r.stopped);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(r.field.width, 125);
    EXPECT_TRUE(describe_invalid(r.field).empty());
    EXPECT_FALSE(verify_field(r.field).orientable());
}

TEST(Generator, HonoursTheTimeLimit) {
    auto o = options(125, 125, 4, 2, 1);
    o.time_limit_s = 0.2;
    auto r = generate_field(o);
    EXPECT_FALSE(r.complete);
    EXPECT_TRUE(r.timed_out);
    EXPECT_LT(r.seconds, 5.0);
}

}  // namespace
