// The default field for a screen exists, covers the screen, and keeps the
// module size the benchmark measured.
#include "shared/field/default_field.hpp"

#include <gtest/gtest.h>

#include "shared/field/field_io.hpp"

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

TEST(DefaultField, HonoursAWantedModuleSizeWhereAShippedFieldCovers) {
    struct Case {
        int w, h;
        double wanted;
        const char* file;
        int module_px;
    } cases[] = {
        {1920, 1080, 30, "b4-64x36.json", 30},   // the default exactly
        {1920, 1080, 40, "b4-64x36.json", 40},   // larger: reaches past the edges
        {1920, 1080, 20.4, "b4-96x54.json", 20}, // smaller: a larger field
        {1920, 1080, 16, "b4-120x68.json", 16},
        {1920, 1080, 8, "b4-120x68.json", 16},   // too small for any: the largest that covers
        {3840, 2160, 48, "b4-96x54.json", 48},   // a 4K screen at 150 % of 32 px
        {1080, 1920, 30, "b4-64x36.json", 30},   // portrait
    };
    for (const auto& c : cases) {
        const umf::DefaultField d = umf::field_for_screen(c.w, c.h, c.wanted);
        EXPECT_EQ(d.file, c.file) << c.w << "x" << c.h << " at " << c.wanted;
        EXPECT_EQ(d.module_px, c.module_px) << c.w << "x" << c.h << " at " << c.wanted;
        const umf::Field f = umf::load_field(std::string(UMF_DATA_DIR) + "/fields/" + d.file);
        const int w = d.quarter_turn ? f.height : f.width, h = d.quarter_turn ? f.width : f.height;
        EXPECT_GE(w * d.module_px, c.w);
        EXPECT_GE(h * d.module_px, c.h);
    }
    const umf::DefaultField fallback = umf::field_for_screen(2560, 1440, 0);
    EXPECT_EQ(fallback.file, umf::default_field_for_screen(2560, 1440).file);
    EXPECT_EQ(fallback.module_px, umf::default_field_for_screen(2560, 1440).module_px);
}
