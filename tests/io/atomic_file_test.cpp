#include "shared/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(AtomicFile, ReplacesContentsWholly) {
    auto dir = fs::temp_directory_path() / "umf_atomic_test";
    fs::create_directories(dir);
    auto path = dir / "f.bin";
    umf::write_file_atomically(path.string(), std::string("first"));
    umf::write_file_atomically(path.string(), std::string("second\0with nul", 15));
    EXPECT_EQ(read(path), std::string("second\0with nul", 15));
    EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
    fs::remove_all(dir);
}

TEST(AtomicFile, FailureLeavesTheOldFileAndNoTemporary) {
    auto dir = fs::temp_directory_path() / "umf_atomic_fail";
    fs::create_directories(dir / "target");  // a directory where the file should go: rename must fail
    EXPECT_THROW(umf::write_file_atomically((dir / "target").string(), "x"), umf::FileWriteError);
    EXPECT_TRUE(fs::is_directory(dir / "target"));
    EXPECT_FALSE(fs::exists(dir / "target.tmp"));
    EXPECT_THROW(umf::write_file_atomically("/nonexistent-dir/f", "x"), umf::FileWriteError);
    fs::remove_all(dir);
}

}  // namespace
