// The one command-line parser of umf-field, umf-provider and umf-requester.
#include "shared/cli/args.hpp"

#include <gtest/gtest.h>

namespace {

using namespace umf::cli;

Args parse(std::vector<std::string> words, const std::vector<std::string>& options,
           const std::vector<std::string>& flags) {
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    return parse_args(static_cast<int>(argv.size()), argv.data(), 0, options, flags);
}

// The message of the UsageError that parsing `words` raises, or "" without one.
std::string refusal(std::vector<std::string> words) {
    try {
        parse(std::move(words), {"out", "module-px"}, {"quiet"});
    } catch (const UsageError& e) {
        return e.what();
    }
    return "";
}

TEST(CliArgs, WordsOptionsAndFlags) {
    const Args a = parse({"f.json", "--out", "x.png", "--module-px=30", "--quiet", "g.json", "--", "--quiet"},
                         {"out", "module-px", "caption"}, {"quiet", "rotate"});
    EXPECT_EQ(a.positional, (std::vector<std::string>{"f.json", "g.json", "--quiet"}));
    EXPECT_EQ(get(a, "out").value_or(""), "x.png");
    EXPECT_EQ(get(a, "module-px").value_or(""), "30");
    EXPECT_TRUE(has_flag(a, "quiet"));
    EXPECT_FALSE(has_flag(a, "rotate"));
    EXPECT_FALSE(get(a, "caption"));
    EXPECT_EQ(get(parse({"--out="}, {"out"}, {}), "out").value_or("x"), "");
}

TEST(CliArgs, UsageErrorsNameTheOption) {
    EXPECT_EQ(refusal({"--out"}), "--out needs a value");
    EXPECT_EQ(refusal({"--width", "3"}), "unknown option --width");
    EXPECT_EQ(refusal({"--loud"}), "unknown option --loud");
    EXPECT_EQ(refusal({"--out", "a", "--out=b"}), "--out is given twice");
    EXPECT_EQ(refusal({"--quiet", "--quiet"}), "--quiet is given twice");
    EXPECT_EQ(refusal({"--quiet=yes"}), "--quiet takes no value");
    EXPECT_EQ(refusal({"--out", "--quiet"}), "");  // a value may look like an option
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
