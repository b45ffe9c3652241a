// The browser companion's pure parts: what a browser's window report may
// carry, which reported window a desktop window is, what a grab takes from a
// page's answer, and the host manifests.
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "provider/browser/base64.hpp"
#include "provider/browser/browser_windows.hpp"
#include "provider/browser/element_content.hpp"
#include "provider/browser/host_manifests.hpp"

namespace umf::provider {
namespace {

using json = nlohmann::json;

json window_json(long id, const std::string& url, const std::string& title, bool incognito = false) {
    return {{"id", id},     {"left", 100},     {"top", 50},
            {"width", 900}, {"height", 650},   {"focused", true},
            {"incognito", incognito}, {"tab", {{"id", id * 10}, {"url", url}, {"title", title}, {"zoom", 1.25}}}};
}

TEST(BrowserWindows, OnlyHttpUrlsMayLeave) {
    EXPECT_TRUE(is_shareable_url("https://example.org/a?b=c#d"));
    EXPECT_TRUE(is_shareable_url("HTTP://example.org"));
    for (const char* url : {"", "file:///etc/passwd", "javascript:alert(1)", "data:text/html,hi", "chrome://settings",
                            "about:blank", "https://", "https://exa mple.org", "https://a\x01.org", "ftp://x.org"})
        EXPECT_FALSE(is_shareable_url(url)) << url;
    EXPECT_FALSE(is_shareable_url("https://example.org/" + std::string(9000, 'a')));
}

TEST(BrowserWindows, PrivateWindowsAndOtherSchemesAreDropped) {
    const json message{{"type", "windows"},
                       {"windows",
                        {window_json(1, "https://example.org/", "Example"),
                         window_json(2, "https://secret.example/", "Secret", true),
                         window_json(3, "file:///home/me/diary.html", "Diary")}}};
    json private_tab = window_json(4, "https://also-secret.example/", "Also secret");
    private_tab["incognito"] = false;
    private_tab["tab"]["incognito"] = true;
    json with_private_tab = message;
    with_private_tab["windows"].push_back(private_tab);
    const auto windows = parse_browser_windows(with_private_tab);
    ASSERT_EQ(windows.size(), 2u);
    EXPECT_EQ(windows[0].tab.url, "https://example.org/");
    EXPECT_EQ(windows[0].tab.zoom, 1.25);
    EXPECT_EQ(windows[0].bounds, (WindowRect{100, 50, 900, 650}));
    EXPECT_EQ(windows[1].id, 3);
    EXPECT_EQ(windows[1].tab.url, "") << "a file: page is kept for matching, its URL is not";
    for (const auto& w : windows) EXPECT_EQ(w.tab.title.find("ecret"), std::string::npos);
}

TEST(BrowserWindows, MalformedReportsAreRefusedAndLongTitlesClipped) {
    EXPECT_THROW(parse_browser_windows(json{{"type", "windows"}}), std::invalid_argument);
    EXPECT_THROW(parse_browser_windows(json{{"windows", {1, 2}}}), std::invalid_argument);
    EXPECT_THROW(parse_browser_windows(json{{"windows", {{{"left", 1}}}}}), std::invalid_argument);
    EXPECT_THROW(parse_browser_windows(json{{"windows", {{{"id", 1}, {"left", 1e300}}}}}), std::invalid_argument);
    json many{{"windows", json::array()}};
    for (int i = 0; i < 300; ++i) many["windows"].push_back(window_json(i, "https://x.org", "x"));
    EXPECT_THROW(parse_browser_windows(many), std::invalid_argument);
    const auto windows = parse_browser_windows(
        json{{"windows", {window_json(1, "https://x.org", std::string(1 << 20, 'T') + "\x1b[2J")}}});
    ASSERT_EQ(windows.size(), 1u);
    EXPECT_LE(windows[0].tab.title.size(), 512u);
}

TEST(BrowserWindows, DesktopWindowsMatchByProcessBoundsAndTitle) {
    BrowserState chromium;
    chromium.connection = 7;
    chromium.pid = 4242;
    chromium.windows = parse_browser_windows(json{{"windows", {window_json(1, "https://a.org/", "Page A")}}});
    chromium.windows.push_back(chromium.windows[0]);
    chromium.windows[1].id = 2;
    chromium.windows[1].bounds = {1000, 0, 600, 400};
    chromium.windows[1].tab.title = "Page B";
    WindowInfo x11;
    x11.pid = 4242;
    x11.rect = {98, 20, 904, 682};  // openbox's frame around it
    x11.title = "Page A - Chromium";
    auto match = match_browser_window({chromium}, x11);
    ASSERT_TRUE(match);
    EXPECT_EQ(match->connection, 7);
    EXPECT_EQ(match->window.id, 1);
    // Another process, another title, or another place: not this browser's.
    x11.pid = 1;
    EXPECT_FALSE(match_browser_window({chromium}, x11));
    x11.pid = 4242;
    x11.title = "Private page - Chromium";  // a private window where a reported one is
    EXPECT_FALSE(match_browser_window({chromium}, x11));
    x11.title = "Page - Chromium";
    EXPECT_FALSE(match_browser_window({chromium}, x11)) << "a shorter title is not the tab's";
    // A long title the browser cut its own way: its first 64 bytes decide.
    const std::string long_title = "A page whose title goes on and on " + std::string(200, 'x');
    chromium.windows[0].tab.title = long_title;
    x11.title = long_title.substr(0, 100) + "… — Mozilla Firefox";
    EXPECT_TRUE(match_browser_window({chromium}, x11));
    x11.title = long_title.substr(0, 40) + "… — Mozilla Firefox";
    EXPECT_FALSE(match_browser_window({chromium}, x11));
    chromium.windows[0].tab.title = "Page A";
    x11.title = "Page A - Chromium";
    x11.rect = {1000, 0, 600, 400};
    EXPECT_FALSE(match_browser_window({chromium}, x11));
    // Wayland: no bounds either side; a unique title decides.
    BrowserState wayland = chromium;
    for (auto& w : wayland.windows) w.bounds = {};
    x11.rect = {};
    x11.title = "Page B — Mozilla Firefox";
    match = match_browser_window({wayland}, x11);
    ASSERT_TRUE(match);
    EXPECT_EQ(match->window.id, 2);
    wayland.windows[0].tab.title = "Page B";
    EXPECT_FALSE(match_browser_window({wayland}, x11)) << "two windows with that title: neither";
}

TEST(BrowserWindows, AWindowThatCannotBeToldFromAnotherMatchesNothing) {
    BrowserState chromium;
    chromium.pid = 4242;
    chromium.windows = parse_browser_windows(json{{"windows", {window_json(1, "https://a.org/", "Page A")}}});
    WindowInfo normal, hidden_private;
    normal.id = 10;
    hidden_private.id = 11;
    for (WindowInfo* w : {&normal, &hidden_private}) {
        w->pid = 4242;
        w->rect = {100, 50, 900, 650};
        w->title = "Page A - Chromium";
    }
    EXPECT_TRUE(match_browser_window({chromium}, normal, {normal}));
    // The private window over the normal one, showing the same page: the
    // report fits both, so neither is taken for it.
    EXPECT_FALSE(match_browser_window({chromium}, hidden_private, {normal, hidden_private}));
    EXPECT_FALSE(match_browser_window({chromium}, normal, {normal, hidden_private}));
    hidden_private.rect = {400, 300, 500, 400};
    EXPECT_TRUE(match_browser_window({chromium}, normal, {normal, hidden_private}));
}

TEST(ElementContent, LinksImagesVideosAndPassages) {
    BrowserTab tab;
    tab.url = "https://docs.example/book/start.html";
    tab.title = "The Book — Getting started";
    Resolved r = content_of_element(json{{"kind", "link"}, {"url", "https://example.org/notes"}, {"text", "Release notes"}}, tab);
    EXPECT_EQ(r.kind, protocol::ContentKind::url);
    EXPECT_EQ(r.url, "https://example.org/notes");
    EXPECT_EQ(r.title, "Link: Release notes");
    r = content_of_element(json{{"kind", "image"}, {"url", "https://docs.example/img/chart.png?v=2"}, {"text", "A chart"}}, tab);
    EXPECT_EQ(r.url, "https://docs.example/img/chart.png?v=2");
    EXPECT_EQ(r.title, "Image: chart.png");
    r = content_of_element(json{{"kind", "video"}, {"url", "https://cdn.example/v.webm"}, {"time", 751.6},
                                {"page", "https://www.youtube.com/watch?v=abc&t=10s"}},
                           tab);
    EXPECT_EQ(r.url, "https://www.youtube.com/watch?v=abc&t=751s");
    EXPECT_EQ(r.title, "Video at 12:31");
    r = content_of_element(json{{"kind", "video"}, {"url", "https://cdn.example/v.webm"}, {"time", 3723}}, tab);
    EXPECT_EQ(r.url, "https://cdn.example/v.webm") << "a site that takes no time: the media itself";
    EXPECT_EQ(r.title, "Video at 1:02:03");
    r = content_of_element(json{{"kind", "text"}, {"start", "The quick brown fox, jumps"}, {"end", "slowly behind the-hills."}}, tab);
    EXPECT_EQ(r.url, tab.url + "#:~:text=The%20quick%20brown%20fox%2C%20jumps,slowly%20behind%20the%2Dhills.");
    EXPECT_EQ(r.title, "Page: The Book — Getting started");
    // A javascript: or data: link, or no answer at all: the page.
    for (const json& e : {json{{"kind", "link"}, {"url", "javascript:alert(1)"}}, json{{"kind", "image"}, {"url", "data:image/png;base64,AA"}},
                          json()}) {
        r = content_of_element(e, tab);
        EXPECT_EQ(r.url, tab.url) << e.dump();
        EXPECT_EQ(r.title, "Page: The Book — Getting started");
    }
    // A web app's route stays, the passage after it.
    tab.url = "https://app.example/#/inbox";
    r = content_of_element(json{{"kind", "text"}, {"start", "Hello"}, {"page", "javascript:x"}}, tab);
    EXPECT_EQ(r.url, "https://app.example/#/inbox:~:text=Hello");
}

TEST(Base64, DecodesWhatBrowsersEncodeAndRefusesTheRest) {
    EXPECT_EQ(base64_decode(""), "");
    EXPECT_EQ(base64_decode("aGk="), "hi");
    EXPECT_EQ(base64_decode("aGk"), "hi");
    EXPECT_EQ(base64_decode("AP8A/w=="), std::string("\0\xff\0\xff", 4));
    EXPECT_EQ(base64_decode("+/+/"), std::string("\xfb\xff\xbf", 3));
    for (const char* bad : {"aG k=", "aGk=a", "a===", "aGk-", "\n"}) EXPECT_FALSE(base64_decode(bad)) << bad;
}

TEST(HostManifests, EveryBrowserGetsItsOwnPlaceAndOnlyTheExtension) {
    HostManifestPlaces places;
    places.home = "/home/ann";
    const auto user = host_manifests("/usr/bin/umf-browser-host", places);
    ASSERT_EQ(user.size(), 4u);
    EXPECT_EQ(user[0].file, "/home/ann/.config/chromium/NativeMessagingHosts/org.umf.browser.json");
    EXPECT_EQ(user[3].file, "/home/ann/.mozilla/native-messaging-hosts/org.umf.browser.json");
    const json chromium = json::parse(user[0].text), firefox = json::parse(user[3].text);
    EXPECT_EQ(chromium["path"], "/usr/bin/umf-browser-host");
    EXPECT_EQ(chromium["type"], "stdio");
    EXPECT_EQ(chromium["allowed_origins"], json({"chrome-extension://" + std::string(kChromiumExtensionId) + "/"}));
    EXPECT_FALSE(chromium.contains("allowed_extensions"));
    EXPECT_EQ(firefox["allowed_extensions"], json({kFirefoxExtensionId}));
    places.system = true;
    places.prefix = "/tmp/stage";
    const auto system = host_manifests("/usr/bin/umf-browser-host", places);
    EXPECT_EQ(system[1].file, "/tmp/stage/etc/opt/chrome/native-messaging-hosts/org.umf.browser.json");
    EXPECT_EQ(system[3].file, "/tmp/stage/usr/lib/mozilla/native-messaging-hosts/org.umf.browser.json");
    EXPECT_THROW(host_manifests("umf-browser-host", places), std::invalid_argument);
}

TEST(HostManifests, TheChromiumIdIsTheExtensionsKeys) {
    std::ifstream in(std::string(UMF_BROWSER_EXTENSION_DIR) + "/manifest.json");
    const json manifest = json::parse(in);
    EXPECT_EQ(chromium_extension_id(manifest.at("key").get<std::string>()), kChromiumExtensionId);
    EXPECT_EQ(manifest["browser_specific_settings"]["gecko"]["id"], kFirefoxExtensionId);
    EXPECT_EQ(manifest["manifest_version"], 3);
}

}  // namespace
}  // namespace umf::provider
#endif
