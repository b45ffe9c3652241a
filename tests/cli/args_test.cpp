// The tools' shared argument parsing.
#include "cli/args.hpp"

#include <gtest/gtest.h>

namespace {

using namespace umf::cli;

Args parse(std::vector<std::string> words, const std::vector<std::string>& flags) {
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    return parse_args(static_cast<int>(argv.size()), argv.data(), 0, flags);
}

TEST(CliArgs, WordsOptionsAndFlags) {
    const Args a = parse({"f.json", "--out", "x.png", "--module-px=30", "--quiet", "g.json"}, {"quiet"});
    EXPECT_EQ(a.positional, (std::vector<std::string>{"f.json", "g.json"}));
    EXPECT_EQ(get(a, "out").value_or(""), "x.png");
    EXPECT_EQ(get(a, "module-px").value_or(""), "30");
    EXPECT_TRUE(has_flag(a, "quiet"));
    EXPECT_FALSE(has_flag(a, "rotate"));
    EXPECT_FALSE(get(a, "caption"));
    EXPECT_NO_THROW(reject_unknown(a, {"out", "module-px"}));
    EXPECT_THROW(reject_unknown(a, {"out"}), UsageError);
}

TEST(CliArgs, UsageErrorsNameTheOption) {
    EXPECT_THROW(parse({"--out"}, {}), UsageError);
    EXPECT_EQ(to_integer("port", "47470", 0, 65535), 47470);
    EXPECT_DOUBLE_EQ(to_number("dpi", "96.5", 1, 1000), 96.5);
    for (const char* bad : {"", "12x", "70000", "-1"}) {
        try {
            to_integer("port", bad, 0, 65535);
            ADD_FAILURE() << bad;
        } catch (const UsageError& e) {
            EXPECT_NE(std::string(e.what()).find("--port"), std::string::npos);
        }
    }
    EXPECT_THROW(to_number("dpi", "nan", 1, 1000), UsageError);
}

}  // namespace
