#include "shared/detect/aim_check.hpp"

#include <gtest/gtest.h>

#include "shared/field/field_io.hpp"
#include "tests/support/shipped_field.hpp"

using namespace umf;
using umf::test::shipped_field;

namespace {

// The modules of field rows r0.. and columns c0.. as read from a view, turn 0;
// the part of the box right of column `bent_from` read one module further
// right (a homography that bends away there).
ModuleGrid read_box(const Field& f, int r0, int c0, int rows, int cols, int bent_from = 1 << 20) {
    ModuleGrid g(rows, cols);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const int c = c0 + j >= bent_from ? c0 + j + 1 : c0 + j;
            if (r0 + i < f.height && c < f.width) g.at(i, j) = static_cast<std::int8_t>(f.at(r0 + i, c));
        }
    g.derive_edges();
    return g;
}

TEST(ModuleGrid, CropKeepsValuesAndEdgesInsideAndUnknownOutside) {
    const Field f = shipped_field("b4-64x36.json");
    const ModuleGrid g = read_box(f, 2, 3, 10, 12);
    const ModuleGrid part = g.crop(-1, 8, 4, 6);
    ASSERT_EQ(part.rows, 4);
    ASSERT_EQ(part.cols, 6);
    for (int j = 0; j < 6; ++j) EXPECT_EQ(part.at(0, j), ModuleGrid::kUnknown);  // row -1 of g
    EXPECT_EQ(part.at(1, 0), g.at(0, 8));
    EXPECT_EQ(part.at(3, 3), g.at(2, 11));
    EXPECT_EQ(part.at(3, 4), ModuleGrid::kUnknown);  // column 12 of g
    EXPECT_EQ(part.right_of(1, 0), g.right_of(0, 8));
    EXPECT_EQ(part.below(1, 2), g.below(0, 10));
    EXPECT_EQ(part.right_of(1, 5), ModuleGrid::kUnknown);  // the crop's last column has no right edge
}

TEST(AimCheck, HoldsWhereTheModulesAroundTheAimReadAsTheField) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json"}) {
        const Field f = shipped_field(name);
        const WindowIndex index(f);
        const ModuleGrid g = read_box(f, 4, 6, 20, 30);
        EXPECT_TRUE(aim_holds(g, 4, 6, Eigen::Vector2d(20.5, 13.2), index, VoteOptions{})) << name;
        EXPECT_TRUE(aim_holds(g, 4, 6, Eigen::Vector2d(7.1, 5.0), index, VoteOptions{})) << name << " near the box's corner";
    }
}

TEST(AimCheck, FailsWhereTheViewBendsAwayByAModuleAtTheAim) {
    for (const char* name : {"b4-64x36.json", "k3e4-64x36.json"}) {
        const Field f = shipped_field(name);
        const WindowIndex index(f);
        // Read right from column 18 on: most of the box is right, the aim's
        // neighbourhood (columns 18-24) is not.
        const ModuleGrid g = read_box(f, 4, 6, 20, 30, 18);
        EXPECT_FALSE(aim_holds(g, 4, 6, Eigen::Vector2d(21.5, 13.5), index, VoteOptions{})) << name;
        EXPECT_TRUE(aim_holds(g, 4, 6, Eigen::Vector2d(10.5, 13.5), index, VoteOptions{})) << name << " left of the bend";
    }
}

TEST(AimCheck, FailsWhereNothingAroundTheAimWasRead) {
    const Field f = shipped_field("b4-64x36.json");
    const WindowIndex index(f);
    ModuleGrid g = read_box(f, 4, 6, 20, 30);
    for (int i = 5; i < 15; ++i)
        for (int j = 10; j < 20; ++j) g.at(i, j) = ModuleGrid::kUnknown;  // a finger over the aim
    g.derive_edges();
    EXPECT_FALSE(aim_holds(g, 4, 6, Eigen::Vector2d(20.5, 14.5), index, VoteOptions{}));
}

TEST(AimCheck, AnAimOffTheFieldHasNothingToCheck) {
    const Field f = shipped_field("b4-64x36.json");
    const WindowIndex index(f);
    const ModuleGrid g = read_box(f, 0, 0, 10, 10);
    EXPECT_TRUE(aim_holds(g, 0, 0, Eigen::Vector2d(-2, 5), index, VoteOptions{}));
    EXPECT_TRUE(aim_holds(g, 0, 0, Eigen::Vector2d(5, f.height + 1.0), index, VoteOptions{}));
}

}  // namespace
