// A screen's own field (screen/field_source.hpp): a seed of its own kept in
// its configuration directory, fields of the shipped sizes made from it,
// verified, kept and found again; another screen's differ.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "provider/common/screen_name.hpp"
#include "provider/screen/field_source.hpp"
#include "provider/screen/screen_field.hpp"
#include "shared/field/field_io.hpp"
#include "shared/field/verifier.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf;
using namespace umf::provider;

std::string read_text(const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(FieldSource, AScreensOwnFieldIsMadeOnceKeptAndVerified) {
    test::TempDir dir;
    const FieldSource source = own_field_source(dir.path);
    ASSERT_TRUE(source.own());
    const std::string seed = read_text(dir.path / "field-seed");
    EXPECT_EQ(seed.size(), 17u) << seed;  // 16 hex digits and a newline
    EXPECT_EQ(own_field_source(dir.path).seed(), source.seed()) << "the seed is kept";

    const ScreenField shipped = screen_field_for(1920, 1080);
    const ScreenField own = screen_field_for(1920, 1080, 0.0, source);
    EXPECT_EQ(own.field.width, 64);
    EXPECT_EQ(own.field.height, 36);
    EXPECT_EQ(own.field.window, shipped.field.window);
    EXPECT_EQ(own.field.colors, shipped.field.colors);
    EXPECT_TRUE(own.placement == shipped.placement) << "the same place and module size as the shipped field";
    EXPECT_NE(own.field.modules, shipped.field.modules);
    EXPECT_EQ(own.field.id, "b4-64x36-" + seed.substr(0, 16));
    EXPECT_TRUE(verify_field(own.field).orientable());
    EXPECT_EQ(fs::path(own.file), dir.path / "fields" / (own.field.id + ".json"));
    EXPECT_EQ(load_field(own.file).modules, own.field.modules);
    EXPECT_EQ(own.field.screen, screen_name()) << "a printed field says which screen it belongs to";
    EXPECT_EQ(load_field(own.file).screen, screen_name());

    // Another process of the same screen reads the kept field, whatever a
    // generator would make now: a kept field that differs is what it shows.
    Field edited = own.field;
    edited.modules[0] ^= 1;
    save_field(edited, own.file);
    EXPECT_EQ(screen_field_for(1920, 1080, 0.0, own_field_source(dir.path)).field.modules, edited.modules);

    // A field kept before fields named their screen is named from then on.
    edited.screen.clear();
    save_field(edited, own.file);
    EXPECT_EQ(screen_field_for(1920, 1080, 0.0, own_field_source(dir.path)).field.screen, screen_name());
    EXPECT_EQ(load_field(own.file).screen, screen_name());
    EXPECT_EQ(load_field(own.file).modules, edited.modules);

    // A 4K screen and a portrait one: the shipped sizes, made from the same seed.
    const ScreenField big = screen_field_for(3840, 2160, 0.0, source);
    EXPECT_EQ(big.field.width, 120);
    EXPECT_TRUE(verify_field(big.field).orientable());
    const ScreenField portrait = screen_field_for(1080, 1920, 0.0, source);
    EXPECT_EQ(portrait.field.id, own.field.id + "-r90");
}

TEST(FieldSource, TwoScreensShowTwoFieldsAndARotatedSeedAThird) {
    test::TempDir a, b;
    const Field fa = screen_field_for(1920, 1080, 0.0, own_field_source(a.path)).field;
    const Field fb = screen_field_for(1920, 1080, 0.0, own_field_source(b.path)).field;
    EXPECT_NE(fa.id, fb.id);
    EXPECT_NE(fa.modules, fb.modules);
    const FieldSource rotated = rotate_field_seed(a.path);
    EXPECT_FALSE(fs::exists(a.path / "fields" / (fa.id + ".json"))) << "the old field's file is gone";
    const Field fc = screen_field_for(1920, 1080, 0.0, rotated).field;
    EXPECT_NE(fc.modules, fa.modules);
    EXPECT_EQ(own_field_source(a.path).seed(), rotated.seed());
}

TEST(FieldSource, ABrokenSeedIsAClearErrorNotANewField) {
    test::TempDir dir;
    for (const char* text : {"", "xyz", "0000000000000000", "12345", "0123456789abcdef0"}) {
        std::ofstream(dir.path / "field-seed") << text;
        try {
            own_field_source(dir.path);
            ADD_FAILURE() << "accepted the seed '" << text << "'";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("not a field seed"), std::string::npos) << e.what();
        }
    }
    EXPECT_FALSE(FieldSource().own());
}

}  // namespace

#endif
