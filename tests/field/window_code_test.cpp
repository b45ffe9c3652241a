#include "shared/field/window_code.hpp"

#include <gtest/gtest.h>

#include "shared/field/window_classes.hpp"
#include "tests/field/test_fields.hpp"

using namespace umf;

namespace {

struct Kind {
    int window, colors;
    WindowKey key;
};

class WindowCodeTest : public ::testing::TestWithParam<Kind> {};

TEST_P(WindowCodeTest, RotatingTheCodeMatchesTurningTheWindow) {
    auto [n, k, key] = GetParam();
    WindowCodec codec(n, k, key);
    Field f = test::random_field(12, 9, n, k, 42, key);
    for (int r = 0; r < f.window_rows(); ++r)
        for (int c = 0; c < f.window_cols(); ++c) {
            std::uint64_t code = codec.code_at(f, r, c);
            ASSERT_LT(code, codec.code_space());
            for (int t = 1; t < 4; ++t) {
                code = codec.rotate(code);
                ASSERT_EQ(code, codec.code_at(f, r, c, t)) << "window (" << r << "," << c << ") turn " << t;
            }
            EXPECT_EQ(codec.rotate(code), codec.code_at(f, r, c)) << "four turns are no turn";
        }
}

TEST_P(WindowCodeTest, RotationsShareTheirCanonicalCode) {
    auto [n, k, key] = GetParam();
    WindowCodec codec(n, k, key);
    Field f = test::random_field(10, 10, n, k, 7, key);
    for (int r = 0; r < f.window_rows(); ++r)
        for (int c = 0; c < f.window_cols(); ++c) {
            auto canon = codec.canonical(codec.code_at(f, r, c));
            for (int t = 1; t < 4; ++t) EXPECT_EQ(canon, codec.canonical(codec.code_at(f, r, c, t)));
            EXPECT_LE(canon, codec.code_at(f, r, c));
        }
}

TEST_P(WindowCodeTest, ClassTableAgreesWithTheCodec) {
    auto [n, k, key] = GetParam();
    WindowCodec codec(n, k, key);
    WindowClasses classes(codec);
    Field f = test::random_field(20, 20, n, k, 3, key);
    for (int r = 0; r < f.window_rows(); ++r)
        for (int c = 0; c < f.window_cols(); ++c) {
            auto code = codec.code_at(f, r, c);
            auto cls = classes.of(code);
            EXPECT_EQ(cls.id, codec.canonical(code));
            EXPECT_EQ(cls.self_symmetric, codec.self_symmetric(code));
        }
}

INSTANTIATE_TEST_SUITE_P(Keys, WindowCodeTest,
                         ::testing::Values(Kind{4, 2, WindowKey::modules}, Kind{3, 2, WindowKey::modules},
                                           Kind{3, 3, WindowKey::modules}, Kind{3, 3, WindowKey::edges},
                                           Kind{3, 5, WindowKey::edges}, Kind{4, 4, WindowKey::edges}),
                         [](const ::testing::TestParamInfo<Kind>& info) {
                             return "n" + std::to_string(info.param.window) + "_k" +
                                    std::to_string(info.param.colors) + "_" + to_string(info.param.key);
                         });

TEST(WindowCode, EdgeCodesIgnoreAbsoluteShades) {
    WindowCodec codec(3, 5, WindowKey::edges);
    Field a = make_field(3, 3, 3, 5, WindowKey::edges);
    a.modules = {0, 1, 2, 1, 1, 0, 2, 3, 1};
    Field b = a;
    for (auto& m : b.modules) m = static_cast<std::uint8_t>(m + 1);  // brighter, same edges
    EXPECT_EQ(codec.code_at(a, 0, 0), codec.code_at(b, 0, 0));
    b.at(1, 1) = 0;  // now the centre is darker than its neighbours
    EXPECT_NE(codec.code_at(a, 0, 0), codec.code_at(b, 0, 0));
}

TEST(WindowCode, UniformAndPointSymmetricWindowsAreSelfSymmetric) {
    WindowCodec codec(4, 2, WindowKey::modules);
    std::uint8_t zeros[16] = {};
    EXPECT_TRUE(codec.self_symmetric(codec.code_of(zeros)));
    // Symmetric under a half turn but not a quarter turn.
    std::uint8_t half[16] = {1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1};
    EXPECT_TRUE(codec.self_symmetric(codec.code_of(half)));
    std::uint8_t corner[16] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    EXPECT_FALSE(codec.self_symmetric(codec.code_of(corner)));
}

TEST(WindowCode, RejectsUnsupportedShapes) {
    EXPECT_THROW(WindowCodec(5, 2, WindowKey::modules), std::invalid_argument);
    EXPECT_THROW(WindowCodec(4, 11, WindowKey::modules), std::invalid_argument);
}

}  // namespace
