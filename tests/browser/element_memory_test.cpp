// What the page last said lay at an aimed point (element_memory.hpp): where
// a page's answer says its element lies, and when a late aim may be given it.
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "provider/browser/element_memory.hpp"

namespace umf::provider {
namespace {

using json = nlohmann::json;
using namespace std::chrono_literals;

BrowserMatch tab_showing(const std::string& url, long tab = 2) {
    BrowserMatch m;
    m.connection = 1;
    m.window.id = 7;
    m.window.tab.id = tab;
    m.window.tab.url = url;
    return m;
}

json link_at(double x, double y, double w, double h) {
    return {{"kind", "link"}, {"url", "https://example.org/notes"}, {"screen_rect", {x, y, w, h}}};
}

TEST(ElementScreenRect, TakesFourFiniteNumbersOfAPlaceOnAScreen) {
    const auto r = element_screen_rect(link_at(10.5, 20.25, 100.2, 30));
    ASSERT_TRUE(r);
    EXPECT_EQ(*r, (WindowRect{10, 20, 101, 30}));
    // Whatever a hostile page sends is no place.
    for (const json& bad : {json(), json::array(), json{{"screen_rect", "10,20,30,40"}},
                            json{{"screen_rect", {1, 2, 3}}}, json{{"screen_rect", {1, 2, 3, 4, 5}}},
                            json{{"screen_rect", {1, 2, "3", 4}}}, json{{"screen_rect", {1, 2, 0, 4}}},
                            json{{"screen_rect", {1, 2, -30, 4}}}, json{{"screen_rect", {1e300, 2, 3, 4}}},
                            json{{"screen_rect", {1, 2, 3e9, 4}}}, json{{"screen_rect", {{1}, 2, 3, 4}}}})
        EXPECT_FALSE(element_screen_rect(bad)) << bad.dump();
}

TEST(ElementMemory, RecallsOnlyInsideTheElementOnTheSameTabForAWhile) {
    ElementMemory memory(3000ms);
    const auto t0 = ElementMemory::Clock::now();
    const BrowserMatch tab = tab_showing("https://example.org/");
    memory.remember(tab, link_at(100, 200, 50, 20), t0);
    const auto kept = memory.recall(tab, 120, 210, t0 + 1s);
    ASSERT_TRUE(kept);
    EXPECT_EQ((*kept)["url"], "https://example.org/notes");
    EXPECT_FALSE(memory.recall(tab, 160, 210, t0 + 1s)) << "beside the link";
    EXPECT_FALSE(memory.recall(tab, 120, 230, t0 + 1s)) << "below the link";
    EXPECT_FALSE(memory.recall(tab, 120, 210, t0 + 4s)) << "too old";
    EXPECT_FALSE(memory.recall(tab_showing("https://example.org/other"), 120, 210, t0 + 1s)) << "the tab went elsewhere";
    EXPECT_FALSE(memory.recall(tab_showing("https://example.org/", 3), 120, 210, t0 + 1s)) << "another tab";
    BrowserMatch other_browser = tab;
    other_browser.connection = 2;
    EXPECT_FALSE(memory.recall(other_browser, 120, 210, t0 + 1s));
}

TEST(ElementMemory, AnAnswerWithoutAPlaceForgetsTheLastOne) {
    ElementMemory memory;
    const BrowserMatch tab = tab_showing("https://example.org/");
    memory.remember(tab, link_at(100, 200, 50, 20));
    ASSERT_TRUE(memory.recall(tab, 120, 210));
    memory.remember(tab, json{{"kind", "link"}, {"url", "https://example.org/x"}});
    EXPECT_FALSE(memory.recall(tab, 120, 210));
    memory.remember(tab, link_at(100, 200, 50, 20));
    json outside = link_at(100, 200, 50, 20);
    outside["kind"] = "outside";
    memory.remember(tab, outside);
    EXPECT_FALSE(memory.recall(tab, 120, 210));
    memory.remember(tab, link_at(100, 200, 50, 20));
    memory.remember(tab, json());  // the page said nothing
    EXPECT_FALSE(memory.recall(tab, 120, 210));
}

}  // namespace
}  // namespace umf::provider
#endif
