// umf-requester discover's pure half: TXT records, the fingerprint check,
// one screen per name whatever the interfaces and protocols, the order and
// the lines. The Avahi half runs against a real daemon in
// tests/discovery/avahi_announcement_test.sh.
#ifdef UMF_REQUESTER_TOOL

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "native/screen_list.hpp"
#include "requester/screen_lines.hpp"

namespace {

using umf::native::is_fingerprint;
using umf::native::ResolvedService;
using umf::native::AnnouncedScreen;
using umf::requester::screen_json;
using umf::requester::screen_line;
using umf::native::screens_from;
using umf::native::txt_value;

const std::string kFp = "1a2b3c4d5e6f708192a3b4c5d6e7f8091a2b3c4d5e6f708192a3b4c5d6e7f809";
const std::string kOtherFp = std::string(64, 'e');

ResolvedService desk(const std::string& address, std::vector<std::string> txt = {"v=1", "fp=" + kFp}) {
    return {"umf on desk", "desk.local", 8443, address, std::move(txt)};
}

TEST(RequesterDiscover, TxtValueTakesTheFirstOccurrenceWithoutCase) {
    EXPECT_EQ(txt_value({"v=1", "fp=abc"}, "fp"), "abc");
    EXPECT_EQ(txt_value({"FP=abc"}, "fp"), "abc");
    EXPECT_EQ(txt_value({"fp=first", "fp=second"}, "fp"), "first");
    EXPECT_EQ(txt_value({"fp="}, "fp"), "");
    EXPECT_EQ(txt_value({"fp=a=b"}, "fp"), "a=b");
    EXPECT_EQ(txt_value({"v=1"}, "fp"), std::nullopt);
    EXPECT_EQ(txt_value({"fpx=1", "f=2"}, "fp"), std::nullopt);
    // A key without "=" is a boolean attribute, and it still hides a later value.
    EXPECT_EQ(txt_value({"fp", "fp=abc"}, "fp"), std::nullopt);
    EXPECT_EQ(txt_value({}, "fp"), std::nullopt);
}

TEST(RequesterDiscover, FingerprintIs64LowercaseHexDigits) {
    EXPECT_TRUE(is_fingerprint(kFp));
    EXPECT_FALSE(is_fingerprint(kFp.substr(1)));
    EXPECT_FALSE(is_fingerprint(kFp + "0"));
    std::string upper = kFp;
    upper[1] = 'A';
    EXPECT_FALSE(is_fingerprint(upper));
    EXPECT_FALSE(is_fingerprint(std::string(63, 'a') + "g"));
    EXPECT_FALSE(is_fingerprint(""));
}

TEST(RequesterDiscover, OneScreenPerNameWithAllItsAddresses) {
    const auto screens = screens_from({desk("fe80::1%umf0"), desk("10.0.0.5"), desk("192.168.1.20"), desk("10.0.0.5"),
                                       desk("")});
    ASSERT_EQ(screens.size(), 1u);
    const AnnouncedScreen& s = screens[0];
    EXPECT_EQ(s.name, "umf on desk");
    EXPECT_EQ(s.host, "desk.local");
    EXPECT_EQ(s.port, 8443);
    EXPECT_EQ(s.addresses, (std::vector<std::string>{"10.0.0.5", "192.168.1.20", "fe80::1%umf0"}));
    EXPECT_EQ(s.fingerprint, kFp);
    EXPECT_EQ(s.version, "1");
    EXPECT_FALSE(s.paired);
}

TEST(RequesterDiscover, SortedByNameAndDroppedWithoutAPort) {
    ResolvedService b = desk("10.0.0.6");
    b.name = "umf on desk (2)";
    ResolvedService a = desk("10.0.0.7");
    a.name = "umf on attic";
    ResolvedService portless = desk("10.0.0.8");
    portless.name = "umf on broken";
    portless.port = 0;
    const auto screens = screens_from({b, desk("10.0.0.5"), portless, a});
    ASSERT_EQ(screens.size(), 3u);
    EXPECT_EQ(screens[0].name, "umf on attic");
    EXPECT_EQ(screens[1].name, "umf on desk");
    EXPECT_EQ(screens[2].name, "umf on desk (2)");
}

TEST(RequesterDiscover, MalformedOrMissingFingerprintIsLeftEmpty) {
    for (const auto& txt : std::vector<std::vector<std::string>>{
             {"v=1"}, {"v=1", "fp=" + kFp.substr(2)}, {"fp=" + std::string(64, 'F')}, {"fp"}}) {
        const auto screens = screens_from({desk("10.0.0.5", txt)}, {kFp});
        ASSERT_EQ(screens.size(), 1u);
        EXPECT_EQ(screens[0].fingerprint, "");
        EXPECT_FALSE(screens[0].paired);  // an empty fingerprint matches nothing
    }
    EXPECT_EQ(screens_from({desk("10.0.0.5", {})})[0].version, "");
}

TEST(RequesterDiscover, PairedFingerprintsMarkTheirScreens) {
    ResolvedService other = desk("10.0.0.9", {"v=1", "fp=" + kOtherFp});
    other.name = "umf on wall";
    const auto screens = screens_from({desk("10.0.0.5"), other}, {kOtherFp});
    ASSERT_EQ(screens.size(), 2u);
    EXPECT_FALSE(screens[0].paired);
    EXPECT_TRUE(screens[1].paired);
    EXPECT_FALSE(screens_from({desk("10.0.0.5")}, {})[0].paired);
    // The pairing URL's and the kept screens' together.
    const auto both = screens_from({desk("10.0.0.5"), other}, {kOtherFp, kFp});
    EXPECT_TRUE(both[0].paired && both[1].paired);
}

TEST(RequesterDiscover, TextLine) {
    auto screens = screens_from({desk("10.0.0.5"), desk("fe80::1%umf0")});
    EXPECT_EQ(screen_line(screens[0]), "umf on desk  https://desk.local:8443  10.0.0.5,fe80::1%umf0  fp " + kFp);
    screens[0].paired = true;
    EXPECT_EQ(screen_line(screens[0]), "umf on desk  https://desk.local:8443  10.0.0.5,fe80::1%umf0  fp " + kFp +
                                           "  (paired)");
    const auto bare = screens_from({desk("", {})});
    EXPECT_EQ(screen_line(bare[0]), "umf on desk  https://desk.local:8443  -  no fingerprint");
}

TEST(RequesterDiscover, TextLineKeepsAHostileNameOnOneLine) {
    ResolvedService r = desk("10.0.0.5");
    r.name = "umf on desk\nfake  https://evil.local:1  1.2.3.4\x1b[2J";
    const std::string line = screen_line(screens_from({r})[0]);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_EQ(line.find('\x1b'), std::string::npos);
    EXPECT_EQ(line.rfind("umf on desk?fake", 0), 0u);
}

TEST(RequesterDiscover, JsonLine) {
    const auto screens = screens_from({desk("10.0.0.5")}, {kFp});
    EXPECT_EQ(screen_json(screens[0], false),
              R"({"name":"umf on desk","host":"desk.local","port":8443,"addresses":["10.0.0.5"],"fingerprint":")" + kFp +
                  R"(","version":"1"})");
    EXPECT_EQ(screen_json(screens[0], true),
              R"({"name":"umf on desk","host":"desk.local","port":8443,"addresses":["10.0.0.5"],"fingerprint":")" + kFp +
                  R"(","version":"1","paired":true})");
    const auto bare = screens_from({desk("", {})});
    EXPECT_EQ(screen_json(bare[0], true),
              R"({"name":"umf on desk","host":"desk.local","port":8443,"addresses":[],"paired":false})");
}

TEST(RequesterDiscover, JsonLineSurvivesBytesThatAreNotUtf8) {
    ResolvedService r = desk("10.0.0.5");
    r.name = "umf on d\xffsk\n";
    const std::string line = screen_json(screens_from({r})[0], false);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_EQ(nlohmann::json::parse(line)["name"], "umf on d\xef\xbf\xbdsk\n");
}

}  // namespace

#endif
