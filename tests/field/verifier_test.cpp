#include "shared/field/verifier.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "shared/field/field_io.hpp"
#include "shared/field/window_code.hpp"
#include "tests/field/test_fields.hpp"

using namespace umf;

namespace {

bool has_conflict(const VerifyReport& r, WindowConflict::Kind kind, int ra, int ca, int rb, int cb, int turns) {
    return std::any_of(r.conflicts.begin(), r.conflicts.end(), [&](const WindowConflict& c) {
        return c.kind == kind && c.row_a == ra && c.col_a == ca && c.row_b == rb && c.col_b == cb &&
               c.quarter_turns == turns;
    });
}

// A 4 x 4 binary block with no symmetry.
const std::uint8_t kBlock[16] = {1, 1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0};

Field two_blocks(bool turn_second) {
    Field f = make_field(9, 4, 4, 2, WindowKey::modules);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            f.at(i, j) = kBlock[i * 4 + j];
            // Turned clockwise: (i, j) shows (3-j, i).
            f.at(i, 5 + j) = turn_second ? kBlock[(3 - j) * 4 + i] : kBlock[i * 4 + j];
        }
    return f;
}

TEST(Verifier, FindsDuplicateWindows) {
    auto report = verify_field(two_blocks(false));
    EXPECT_FALSE(report.orientable());
    EXPECT_TRUE(has_conflict(report, WindowConflict::Kind::duplicate, 0, 0, 0, 5, 0));
}

TEST(Verifier, FindsRotatedWindows) {
    auto report = verify_field(two_blocks(true));
    EXPECT_FALSE(report.orientable());
    // The second block is the first turned by 90 degrees, so turning it by 270 more gives the first back.
    EXPECT_TRUE(has_conflict(report, WindowConflict::Kind::rotated, 0, 0, 0, 5, 3));
    EXPECT_EQ(describe(report.conflicts.front()).find("window (0,0) equals window (0,5) turned 270 degrees"), 0u)
        << describe(report.conflicts.front());
}

TEST(Verifier, FindsSelfSymmetricWindows) {
    Field f = make_field(4, 4, 4, 2, WindowKey::modules);  // all zero: equal to itself at every turn
    auto report = verify_field(f);
    ASSERT_EQ(report.conflicts.size(), 1u);
    EXPECT_EQ(report.conflicts[0].kind, WindowConflict::Kind::self);
    EXPECT_EQ(report.conflicts[0].quarter_turns, 1);
    f.modules = {1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1};  // half-turn symmetric only
    report = verify_field(f);
    ASSERT_EQ(report.conflicts.size(), 1u);
    EXPECT_EQ(report.conflicts[0].quarter_turns, 2);
    EXPECT_NE(describe(report.conflicts[0]).find("equals itself turned 180 degrees"), std::string::npos);
}

TEST(Verifier, EdgeKeysCompareSignsNotShades) {
    // The second 3 x 3 block is the first one shade brighter: different modules, same edges.
    Field f = make_field(7, 3, 3, 3, WindowKey::edges);
    const std::uint8_t block[9] = {0, 1, 1, 1, 0, 0, 0, 0, 1};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            f.at(i, j) = block[i * 3 + j];
            f.at(i, 4 + j) = static_cast<std::uint8_t>(block[i * 3 + j] + 1);
        }
    auto report = verify_field(f);
    EXPECT_TRUE(has_conflict(report, WindowConflict::Kind::duplicate, 0, 0, 0, 4, 0));
    f.key = WindowKey::modules;
    EXPECT_FALSE(has_conflict(verify_field(f), WindowConflict::Kind::duplicate, 0, 0, 0, 4, 0));
}

TEST(Verifier, ListsEveryConflictOfARandomField) {
    // A random 40 x 40 binary field has many conflicts; each listed pair must really conflict.
    Field f = test::random_field(40, 40, 4, 2, 11);
    auto report = verify_field(f);
    ASSERT_GT(report.conflicts.size(), 10u);
    WindowCodec codec(4, 2, WindowKey::modules);
    for (const auto& c : report.conflicts)
        EXPECT_EQ(codec.code_at(f, c.row_a, c.col_a), codec.code_at(f, c.row_b, c.col_b, c.quarter_turns))
            << describe(c);
}

TEST(Verifier, AcceptsTheOriginalAuthorsFields) {
    for (const char* name : {"original-umf/sog5-19x31.json", "original-umf/sog3-16x12.json"}) {
        Field f = load_field(test::data_path(name));
        EXPECT_EQ(f.key, WindowKey::edges);
        auto report = verify_field(f);
        EXPECT_TRUE(report.orientable()) << name << ": " << (report.conflicts.empty() ? "" : describe(report.conflicts[0]));
        EXPECT_EQ(report.windows, f.window_count());
    }
}

TEST(Verifier, OriginalCsvAgreesWithJson) {
    // The published CSV: width, height, "window;torus", a type code, then rows of ';'-separated values.
    for (const char* stem : {"original-umf/sog5-19x31", "original-umf/sog3-16x12"}) {
        Field json_field = load_field(test::data_path(std::string(stem) + ".json"));
        std::ifstream csv(test::data_path(std::string(stem) + ".csv"));
        ASSERT_TRUE(csv) << stem;
        int width = 0, height = 0;
        std::string line;
        std::getline(csv, line);
        width = std::stoi(line);
        std::getline(csv, line);
        height = std::stoi(line);
        std::getline(csv, line);
        EXPECT_EQ(std::stoi(line.substr(0, line.find(';'))), json_field.window);
        std::getline(csv, line);  // type code
        ASSERT_EQ(width, json_field.width);
        ASSERT_EQ(height, json_field.height);
        for (int r = 0; r < height; ++r) {
            ASSERT_TRUE(std::getline(csv, line));
            std::stringstream row(line);
            std::string cell;
            for (int c = 0; c < width; ++c) {
                ASSERT_TRUE(std::getline(row, cell, ';'));
                EXPECT_EQ(std::stoi(cell), json_field.at(r, c)) << stem << " row " << r << " col " << c;
            }
        }
    }
}

}  // namespace
