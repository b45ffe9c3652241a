#include "shared/field/field_io.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tests/field/test_fields.hpp"
#include "tests/support/replaced.hpp"

using namespace umf;

namespace {

using umf::test::replaced;

std::string good_json() {
    return R"({"format": "umf-field/1", "id": "t", "width": 5, "height": 4, "window": 3, "colors": 3,
               "key": "edges", "palette": ["#000000", "#808080", "#ffffff"],
               "rows": ["01201", "12010", "20102", "01021"]})";
}

// The message must name the problem: each case below checks its own words.
void expect_error(const std::string& text, const std::string& words) {
    try {
        parse_field(text, "case.json");
        ADD_FAILURE() << "accepted: " << text.substr(0, 200);
    } catch (const FieldFileError& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(words), std::string::npos) << "message: " << msg << "\nexpected words: " << words;
        EXPECT_EQ(msg.rfind("case.json: ", 0), 0u) << msg;
    }
}

TEST(FieldIo, ParsesAValidFile) {
    Field f = parse_field(good_json());
    EXPECT_EQ(f.id, "t");
    EXPECT_EQ(f.width, 5);
    EXPECT_EQ(f.height, 4);
    EXPECT_EQ(f.window, 3);
    EXPECT_EQ(f.colors, 3);
    EXPECT_EQ(f.key, WindowKey::edges);
    EXPECT_EQ(f.at(1, 0), 1);
    EXPECT_EQ(f.at(3, 4), 1);
    EXPECT_EQ(f.palette[1], "#808080");
}

TEST(FieldIo, RoundTripsThroughTextAndFiles) {
    for (int colors : {2, 3, 7}) {
        Field f = test::random_field(17, 9, colors == 2 ? 4 : 3, colors, 5, default_key(colors));
        f.id = "round \"trip\" " + std::to_string(colors);
        Field back = parse_field(field_to_json(f));
        EXPECT_EQ(back.modules, f.modules);
        EXPECT_EQ(back.id, f.id);
        EXPECT_EQ(back.key, f.key);
        EXPECT_EQ(back.palette, f.palette);

        auto path = std::filesystem::temp_directory_path() / ("umf_io_" + std::to_string(colors) + ".json");
        save_field(f, path.string());
        Field loaded = load_field(path.string());
        EXPECT_EQ(loaded.modules, f.modules);
        EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
        std::filesystem::remove(path);
    }
}

TEST(FieldIo, AScreensNameTravelsWithItsField) {
    Field f = test::random_field(8, 6, 4, 2, 3, WindowKey::modules);
    EXPECT_EQ(field_to_json(f).find("\"screen\""), std::string::npos) << "a field of any screen names none";
    f.screen = "lab-desk-3";
    EXPECT_EQ(parse_field(field_to_json(f)).screen, "lab-desk-3");
    std::string text = field_to_json(f);
    const std::string named = "\"screen\": \"lab-desk-3\"";
    ASSERT_NE(text.find(named), std::string::npos) << text;
    EXPECT_THROW(parse_field(std::string(text).replace(text.find(named), named.size(), "\"screen\": 3")),
                 FieldFileError);
    EXPECT_THROW(parse_field(std::string(text).replace(text.find(named), named.size(),
                                                       "\"screen\": \"" + std::string(256, 'a') + "\"")),
                 FieldFileError);
}

TEST(FieldIo, MissingKeyAndPaletteTakeDefaults) {
    std::string text = R"({"format": "umf-field/1", "width": 4, "height": 4, "window": 4, "colors": 2,
                           "rows": ["0110", "1001", "0011", "1100"]})";
    Field f = parse_field(text);
    EXPECT_EQ(f.key, WindowKey::modules);
    EXPECT_EQ(f.palette, (std::vector<std::string>{"#000000", "#ffffff"}));
}

TEST(FieldIo, RejectsEveryMalformedInput) {
    const std::string g = good_json();
    expect_error("", "not valid JSON");
    expect_error("{\"format\": ", "not valid JSON");
    expect_error("[1, 2]", "top level must be a JSON object");
    expect_error(replaced(g, "\"format\": \"umf-field/1\",", ""), "missing \"format\"");
    expect_error(replaced(g, "umf-field/1", "umf-field/2"), "format is \"umf-field/2\"");
    expect_error(replaced(g, "\"width\": 5", "\"width\": \"5\""), "\"width\" must be an integer");
    expect_error(replaced(g, "\"width\": 5,", ""), "missing \"width\"");
    expect_error(replaced(g, "\"width\": 5", "\"width\": 99999"), "above the limit");
    expect_error(replaced(g, "\"height\": 4", "\"height\": 1000000000"), "out of range");
    expect_error(replaced(g, "\"width\": 5", "\"width\": -5"), "out of range");
    expect_error(replaced(g, "\"window\": 3", "\"window\": 5"), "window must be 3 or 4");
    expect_error(replaced(g, "\"colors\": 3", "\"colors\": 1"), "colors must be 2..10");
    expect_error(replaced(g, "\"colors\": 3", "\"colors\": 11"), "colors must be 2..10");
    expect_error(replaced(g, "\"edges\"", "\"corners\""), "key is \"corners\"");
    expect_error(replaced(g, "\"12010\"", "\"1201\""), "row 1 has 4 modules but width is 5");
    expect_error(replaced(g, "\"12010\"", "\"120100\""), "row 1 has 6 modules but width is 5");
    expect_error(replaced(g, "\"12010\", ", ""), "\"rows\" has 3 rows but height is 4");
    expect_error(replaced(g, "\"20102\"", "\"20302\""), "row 2, column 2: '3' is not a digit 0..2");
    expect_error(replaced(g, "\"20102\"", "\"20x02\""), "row 2, column 2: 'x'");
    expect_error(replaced(g, "\"20102\"", "20102"), "row 2 is not a string");
    expect_error(replaced(g, "\"rows\"", "\"lines\""), "missing \"rows\"");
    expect_error(replaced(g, ", \"#ffffff\"", ""), "palette has 2 entries for 3 colours");
    expect_error(replaced(g, "\"#808080\"", "\"grey\""), "palette entry 'grey'");
    expect_error(R"({"format": "umf-field/1", "width": 2, "height": 3, "window": 3, "colors": 2,
                     "rows": ["01", "10", "11"]})",
                 "has no 3 x 3 window");
    expect_error(std::string(kMaxFieldFileBytes + 1, ' '), "more than the limit");
}

TEST(FieldIo, ReportsUnreadableAndOversizedFiles) {
    EXPECT_THROW(load_field("/nonexistent/field.json"), FieldFileError);
    auto dir = std::filesystem::temp_directory_path();
    auto big = dir / "umf_io_big.json";
    {
        std::ofstream out(big, std::ios::binary);
        out.seekp(static_cast<std::streamoff>(kMaxFieldFileBytes) + 10);
        out.put(' ');
    }
    try {
        load_field(big.string());
        ADD_FAILURE() << "an oversized file was read";
    } catch (const FieldFileError& e) {
        EXPECT_NE(std::string(e.what()).find("more than the limit"), std::string::npos) << e.what();
    }
    std::filesystem::remove(big);
    // A directory is not a field file either.
    EXPECT_THROW(load_field(dir.string()), FieldFileError);
}

TEST(FieldIo, SavingNeverLeavesAHalfWrittenFile) {
    Field bad = make_field(5, 5, 3, 2, WindowKey::modules);
    bad.modules[3] = 7;  // out of range: refused before anything is written
    auto path = std::filesystem::temp_directory_path() / "umf_io_refused.json";
    std::filesystem::remove(path);
    EXPECT_THROW(save_field(bad, path.string()), std::invalid_argument);
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_THROW(save_field(make_field(5, 5, 3, 2, WindowKey::modules), "/nonexistent/dir/f.json"), FieldFileError);
}

}  // namespace
