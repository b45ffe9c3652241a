// The umf-field command as a user runs it: exit codes, files, messages.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Run {
    int code;
    std::string output;  // stdout and stderr
};

Run run(const std::string& args) {
    std::string cmd = std::string(UMF_FIELD_TOOL) + " " + args + " 2>&1";
    Run r{-1, {}};
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = fread(buf.data(), 1, buf.size(), p)) r.output.append(buf.data(), n);
    int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("umf_cli_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

TEST_F(Cli, GenerateVerifyRenderInfo) {
    auto g = run("generate --width 32 --height 18 --seed 3 --quiet --out " + path("f.json"));
    ASSERT_EQ(g.code, 0) << g.output;
    EXPECT_NE(g.output.find("verified"), std::string::npos) << g.output;

    auto v = run("verify " + path("f.json"));
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_NE(v.output.find("4-orientable"), std::string::npos);

    for (const char* ext : {"png", "svg", "pdf"}) {
        auto r = run("render " + path("f.json") + " --module-px 8 --quiet-zone 1 --caption hello --out " +
                     path(std::string("f.") + ext));
        EXPECT_EQ(r.code, 0) << r.output;
        EXPECT_GT(fs::file_size(path(std::string("f.") + ext)), 100u) << ext;
    }
    std::ifstream png(path("f.png"), std::ios::binary);
    char sig[8] = {};
    png.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");

    auto i = run("info --json " + path("f.json"));
    ASSERT_EQ(i.code, 0) << i.output;
    auto info = nlohmann::json::parse(i.output);
    EXPECT_EQ(info["width"], 32);
    EXPECT_EQ(info["windows"], 29 * 15);
    EXPECT_EQ(info["orientable"], true);
}

// A PNG's height, from its IHDR chunk.
unsigned png_height(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char b[24] = {};
    in.read(reinterpret_cast<char*>(b), sizeof b);
    return (b[20] << 24) | (b[21] << 16) | (b[22] << 8) | b[23];
}

TEST_F(Cli, AScreensOwnFieldIsPrintedWithItsScreen) {
    ASSERT_EQ(run("generate --width 32 --height 18 --seed 5 --quiet --id b4-32x18-own --out " + path("f.json")).code,
              0);
    nlohmann::json f = nlohmann::json::parse(std::ifstream(path("f.json")));
    f["screen"] = "lab-desk-3";
    std::ofstream(path("own.json")) << f.dump();

    ASSERT_EQ(run("render " + path("f.json") + " --module-px 8 --out " + path("plain.png")).code, 0);
    auto r = run("render " + path("own.json") + " --module-px 8 --out " + path("own.png"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_GT(png_height(path("own.png")), png_height(path("plain.png"))) << "a caption band under the field";
    ASSERT_EQ(run("render " + path("own.json") + " --module-px 8 --out " + path("own.svg")).code, 0);
    std::ifstream svg(path("own.svg"));
    const std::string text(std::istreambuf_iterator<char>(svg), {});
    EXPECT_NE(text.find("screen lab-desk-3, field b4-32x18-own"), std::string::npos) << text.substr(0, 400);
    ASSERT_EQ(run("render " + path("own.json") + " --module-px 8 --caption \"\" --out " + path("bare.png")).code, 0);
    EXPECT_EQ(png_height(path("bare.png")), png_height(path("plain.png"))) << "--caption \"\" prints none";

    auto info = run("info " + path("own.json"));
    EXPECT_NE(info.output.find("screen      lab-desk-3"), std::string::npos) << info.output;
    EXPECT_EQ(nlohmann::json::parse(run("info --json " + path("own.json")).output)["screen"], "lab-desk-3");
    EXPECT_FALSE(nlohmann::json::parse(run("info --json " + path("f.json")).output).contains("screen"));
}

TEST_F(Cli, VerifyListsConflictsAndFails) {
    std::ofstream(path("bad.json")) << R"({"format": "umf-field/1", "width": 4, "height": 4, "window": 4,
        "colors": 2, "rows": ["0000", "0000", "0000", "0000"]})";
    auto v = run("verify " + path("bad.json"));
    EXPECT_EQ(v.code, 1) << v.output;
    EXPECT_NE(v.output.find("NOT 4-orientable"), std::string::npos) << v.output;
    EXPECT_NE(v.output.find("window (0,0) equals itself turned 90 degrees"), std::string::npos) << v.output;
}

TEST_F(Cli, MalformedFilesExitWithThree) {
    std::ofstream(path("broken.json")) << "{\"format\": \"umf-field/1\", ";
    auto v = run("verify " + path("broken.json"));
    EXPECT_EQ(v.code, 3) << v.output;
    EXPECT_NE(v.output.find("not valid JSON"), std::string::npos) << v.output;
    EXPECT_EQ(run("info " + path("missing.json")).code, 3);
    EXPECT_EQ(run("render " + path("missing.json") + " --out " + path("x.png")).code, 3);
}

TEST_F(Cli, WrongUsageExitsWithTwo) {
    EXPECT_EQ(run("").code, 2);
    EXPECT_EQ(run("frobnicate").code, 2);
    EXPECT_EQ(run("generate --width 10").code, 2);
    EXPECT_EQ(run("generate --width ten --height 10 --out " + path("x.json")).code, 2);
    EXPECT_EQ(run("generate --width 10 --height 10 --colours 3 --out " + path("x.json")).code, 2);
    EXPECT_EQ(run("generate --width 200 --height 200 --out " + path("x.json")).code, 2);  // above the bound
    EXPECT_EQ(run("verify").code, 2);
    auto r = run("render " + path("x.json") + " --out " + path("x.jpg"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_FALSE(fs::exists(path("x.json")));
    auto help = run("--help");
    EXPECT_EQ(help.code, 0);
    EXPECT_NE(help.output.find("exit codes"), std::string::npos);
    EXPECT_EQ(run("verify --help").code, 0);
}

TEST_F(Cli, TimeLimitSavesThePartialFieldAndExitsWithFour) {
    auto g = run("generate --width 125 --height 125 --time-limit 0.3 --quiet --out " + path("big.json"));
    EXPECT_EQ(g.code, 4) << g.output;
    EXPECT_FALSE(fs::exists(path("big.json")));
    ASSERT_TRUE(fs::exists(path("big.partial.json"))) << g.output;
    auto v = run("verify --max-listed 3 " + path("big.partial.json"));
    EXPECT_EQ(v.code, 1);
    EXPECT_NE(v.output.find("more (--max-listed N shows more)"), std::string::npos) << v.output;
}

}  // namespace
