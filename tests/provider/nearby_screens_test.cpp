// The nearby screens a provider lists for its page: from what Avahi resolved,
// only other screens, only at .local names a link can safely name, by name
// and at most kMaxNearbyScreens; the list's JSON; a real browse against a
// daemon is tests/discovery/nearby_screen_test.sh.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "provider/discovery/nearby_screens.hpp"

namespace {

using umf::native::AnnouncedScreen;
using namespace umf::provider;

const std::string kOwn(64, 'a');

AnnouncedScreen screen(std::string name, std::string host, unsigned short port, std::string fingerprint) {
    AnnouncedScreen s;
    s.name = std::move(name);
    s.host = std::move(host);
    s.port = port;
    s.fingerprint = std::move(fingerprint);
    return s;
}

TEST(NearbyScreens, OtherScreensAtLocalNamesByName) {
    const auto list = nearby_from({screen("umf on desk (2)", "desk.local", 9443, std::string(64, 'c')),
                                   screen("umf on desk", "desk.local", 8443, kOwn),  // this screen
                                   screen("umf on lab", "lab-3.local", 8443, std::string(64, 'b')),
                                   screen("umf on nofp", "nofp.local", 8443, ""),
                                   screen("umf on far", "far.example.com", 8443, std::string(64, 'd')),
                                   screen("umf on odd", "a/b@c.local", 8443, std::string(64, 'e')),
                                   screen("umf on dots", "..local", 8443, std::string(64, 'f')),
                                   screen("umf on bare", ".local", 8443, std::string(64, '1'))},
                                  kOwn);
    ASSERT_EQ(list.size(), 2u);
    EXPECT_EQ(list[0], (NearbyScreen{"umf on desk (2)", "https://desk.local:9443", std::string(64, 'c')}));
    EXPECT_EQ(list[1], (NearbyScreen{"umf on lab", "https://lab-3.local:8443", std::string(64, 'b')}));
}

TEST(NearbyScreens, ARoomFullIsCut) {
    std::vector<AnnouncedScreen> many;
    for (int i = 0; i < 40; ++i)
        many.push_back(screen("umf on s" + std::to_string(100 + i), "s" + std::to_string(i) + ".local", 8443,
                              std::string(64, 'b')));
    const auto list = nearby_from(many, kOwn);
    ASSERT_EQ(list.size(), kMaxNearbyScreens);
    EXPECT_EQ(list.front().name, "umf on s100");
}

TEST(NearbyScreens, TheListAsJsonAndItsChanges) {
    NearbyScreens screens;
    EXPECT_EQ(nearby_json(screens.list()), R"({"screens":[]})");
    const std::vector<NearbyScreen> one{{"umf on \"x\"\xff", "https://x.local:1", std::string(64, 'b')}};
    EXPECT_TRUE(screens.set(one));
    EXPECT_FALSE(screens.set(one));
    const auto j = nlohmann::json::parse(nearby_json(screens.list()));
    EXPECT_EQ(j["screens"][0]["name"], "umf on \"x\"\xef\xbf\xbd");  // not UTF-8: replaced
    EXPECT_EQ(j["screens"][0]["origin"], "https://x.local:1");
    EXPECT_EQ(j["screens"][0]["fingerprint"], std::string(64, 'b'));
    EXPECT_TRUE(screens.set({}));
}

}  // namespace

#endif
