// The screens umf-requester keeps (requester/paired_screens.hpp): read and
// written again, one pairing per screen root, the one used last first, 0600,
// and a file that is not such a list left as it is with a clear error.
#ifdef UMF_REQUESTER_TOOL

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "requester/cli.hpp"
#include "requester/paired_screens.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using namespace umf::requester;

PairedScreen screen(const std::string& name, char fingerprint_digit, const std::string& host) {
    PairedScreen s;
    s.name = name;
    s.url_text = umf::protocol::format_pairing_url(host, 47470, std::string(22, 'T'), std::string(64, fingerprint_digit));
    s.url = umf::protocol::parse_pairing_url(s.url_text);
    return s;
}

std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(PairedScreens, KeptReadAgainOnePerScreenUsedLastFirst) {
    umf::test::TempDir dir;
    const auto file = dir.path / "umf" / "requester-screens.json";
    EXPECT_TRUE(read_paired_screens(file).empty()) << "no file: no screens";

    std::vector<PairedScreen> kept = with_screen_first({}, screen("desk-1", 'a', "192.168.1.20"));
    kept = with_screen_first(kept, screen("desk-2", 'b', "192.168.1.21"));
    // desk-1 paired again: a new address (and token), the same root.
    kept = with_screen_first(kept, screen("desk-1", 'a', "192.168.1.30"));
    write_paired_screens(file, kept);

    struct stat st {};
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u) << "pairing URLs carry tokens";
    const auto back = read_paired_screens(file);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].name, "desk-1");
    EXPECT_EQ(back[0].url.host, "192.168.1.30");
    EXPECT_EQ(back[1].name, "desk-2");
    EXPECT_EQ(back[1].url_text, kept[1].url_text);

    std::vector<PairedScreen> fewer = back;
    EXPECT_FALSE(forget_screen(fewer, "desk-9"));
    EXPECT_TRUE(forget_screen(fewer, back[1].url_text)) << "by URL";
    EXPECT_TRUE(forget_screen(fewer, "desk-1")) << "by name";
    EXPECT_TRUE(fewer.empty());

    std::vector<PairedScreen> many;
    for (int i = 0; i < 40; ++i)
        many = with_screen_first(many, screen("s" + std::to_string(i), "0123456789abcdef"[i % 16], "10.0.0." + std::to_string(i)));
    EXPECT_EQ(many.size(), 16u) << "one per root";
    EXPECT_EQ(many.front().name, "s39");
}

TEST(PairedScreens, AFileThatIsNoSuchListIsAnErrorAndLeftAlone) {
    umf::test::TempDir dir;
    const auto file = dir.path / "requester-screens.json";
    for (const std::string& text :
         {std::string("not json"), std::string(R"({"format": "other/1", "screens": []})"),
          std::string(R"({"format": 3, "screens": []})"), std::string(R"([])"),
          std::string(R"({"format": "umf-requester-screens/1", "screens": [{"name": "x"}]})"),
          std::string(R"({"format": "umf-requester-screens/1", "screens": [{"name": "x", "url": "https://h/"}]})")}) {
        std::ofstream(file) << text;
        try {
            read_paired_screens(file);
            ADD_FAILURE() << "accepted " << text;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        }
        EXPECT_EQ(read_text(file), text) << "left as it was";
    }
}

}  // namespace

#endif
