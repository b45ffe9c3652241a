// The default field for a screen exists, covers the screen, and keeps the
// module size the benchmark measured.
#include "field/default_field.hpp"

#include <gtest/gtest.h>

#include "field/field_io.hpp"

TEST(DefaultField, CoversCommonScreensWithShippedFields) {
    struct Case {
        int w, h;
        const char* file;
        int module_px;
    } cases[] = {{1920, 1080, "b4-64x36.json", 30}, {2560, 1440, "b4-64x36.json", 40},
                 {1366, 768, "b4-64x36.json", 22},  {3840, 2160, "b4-120x68.json", 32},
                 {1080, 1920, "b4-64x36.json", 30}};
    for (const auto& c : cases) {
        const umf::DefaultField d = umf::default_field_for_screen(c.w, c.h);
        EXPECT_EQ(d.file, c.file) << c.w << "x" << c.h;
        EXPECT_EQ(d.module_px, c.module_px) << c.w << "x" << c.h;
        const umf::Field f = umf::load_field(std::string(UMF_DATA_DIR) + "/fields/" + d.file);
        EXPECT_EQ(d.quarter_turn, c.h > c.w);
        const int w = d.quarter_turn ? f.height : f.width, h = d.quarter_turn ? f.width : f.height;
        EXPECT_GE(w * d.module_px, c.w);
        EXPECT_GE(h * d.module_px, c.h);
    }
}
