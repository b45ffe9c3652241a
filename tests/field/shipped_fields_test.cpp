// The fields that ship in shared/data/fields must load and verify.
#include <gtest/gtest.h>

#include <filesystem>

#include "shared/field/field_io.hpp"
#include "shared/field/verifier.hpp"

namespace fs = std::filesystem;

TEST(ShippedFields, AllVerify) {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(UMF_DATA_DIR "/fields")) {
        if (entry.path().extension() != ".json") continue;
        ++count;
        umf::Field f = umf::load_field(entry.path().string());
        auto report = umf::verify_field(f);
        EXPECT_TRUE(report.orientable()) << entry.path() << ": " << report.conflicts.size() << " conflicts";
        // The file name is the id without its seed suffix.
        EXPECT_EQ(f.id.rfind(entry.path().stem().string() + "-s", 0), 0u) << entry.path() << " has id " << f.id;
    }
    EXPECT_GE(count, 6);
}
