// The browser companion with the real browsers (browser_bench.hpp): grabs and
// aims at a page's link, image, video and passage, a URL put as a tab there,
// hostile pages, a private window, and no companion at all.
#ifdef UMF_PROVIDER_TESTS
#include "provider/browser/element_memory.hpp"
#include "tests/browser/browser_bench.hpp"

namespace umf::provider::browser_test {
namespace {

TEST_P(BrowserCompanion, GrabsAndAimsTakeTheLinkImageVideoAndPassageUnderThePoint) {
    const std::string page = origin + "/index.html";
    open_page(page);
    const WindowInfo window = *page_window();
    EXPECT_EQ(window.pid, link->browsers().at(0).pid) << "the host's parent is the browser that owns the window";

    struct Case {
        const char* what;
        Spot spot;
        std::string title, url;
    };
    const std::vector<Case> cases = {
        {"link", kLink, "Link: Release notes", "https://example.org/release-notes"},
        {"image", kImage, "Image: chart.png", origin + "/chart.png"},  // an aim; a grab brings the bytes
        {"video", kVideo, "Video at 0:00", origin + "/clip.webm"},
        {"passage", kText, "Page: Companion test page",
         page + "#:~:text=Passage%20number%2015%20begins%20here,evening%20light%20over%20field%2015"},
    };
    for (const Case& c : cases) {
        for (const Purpose purpose : {Purpose::grab, Purpose::preview}) {
            const auto resolved = resolver->resolve(point_on(window, c.spot), purpose);
            ASSERT_TRUE(resolved) << c.what;
            if (purpose == Purpose::grab && c.spot.left == kImage.left && c.spot.bottom == kImage.bottom) {
                EXPECT_EQ(resolved->kind, protocol::ContentKind::file);
                EXPECT_EQ(resolved->title, "Image: chart.png");
                EXPECT_EQ(resolved->name, "chart.png");
                EXPECT_EQ(resolved->mime, "image/png");
                ASSERT_TRUE(resolved->bytes);
                EXPECT_EQ(*resolved->bytes, tiny_png()) << "the image's own bytes";
                continue;
            }
            EXPECT_EQ(resolved->kind, protocol::ContentKind::url) << c.what;
            EXPECT_EQ(resolved->title, c.title) << c.what << (purpose == Purpose::grab ? " grab" : " aim");
            EXPECT_EQ(resolved->url, c.url) << c.what << (purpose == Purpose::grab ? " grab" : " aim");
        }
    }
    // The page says where the link lies on the screen, so that a late aim
    // inside it keeps it (element_memory.hpp).
    const ScreenPoint centre = point_on(window, kLink);
    const BrowserWindow shown = *reported(page);
    const auto answer = link->ask(link->browsers().at(0).connection,
                                  {{"type", "element_at"}, {"window", shown.id}, {"tab", shown.tab.id},
                                   {"screen_x", centre.root_x}, {"screen_y", centre.root_y}},
                                  5s);
    ASSERT_TRUE(answer);
    const auto rect = element_screen_rect(answer->value("element", nlohmann::json()));
    ASSERT_TRUE(rect) << answer->dump();
    EXPECT_NEAR(rect->x, window.rect.x + kLink.left, 4) << answer->dump();
    EXPECT_TRUE(rect->contains(centre.root_x, centre.root_y)) << answer->dump();
    // Firefox's viewport ends a few pixels above its window's bottom edge.
    EXPECT_NEAR(rect->y, window.rect.y + window.rect.height - kLink.bottom - kLink.height, 8) << answer->dump();
    EXPECT_NEAR(rect->width, kLink.width, 4) << answer->dump();
    EXPECT_NEAR(rect->height, kLink.height, 4) << answer->dump();
    // Off the page (the browser's toolbar): the page itself.
    const auto toolbar = resolver->resolve(ScreenPoint{0, window.rect.x + 300.0, window.rect.y + 10.0,
                                                       window.rect.x + 300.0, window.rect.y + 10.0},
                                           Purpose::grab);
    ASSERT_TRUE(toolbar);
    EXPECT_EQ(toolbar->url, page);
    EXPECT_EQ(toolbar->title, "Page: Companion test page");
}

TEST_P(BrowserCompanion, AUrlPutOnTheWindowOpensAsATabThere) {
    const std::string page = origin + "/index.html", put = origin + "/index.html?put=1";
    open_page(page);
    const BrowserWindow before = *reported(page);
    const WindowInfo window = *page_window();
    const ScreenPoint at = point_on(window, kText);
    EXPECT_FALSE(resolver->open_tab_at(at, "javascript:alert(1)"));
    EXPECT_FALSE(resolver->open_tab_at(at, "file:///etc/passwd"));
    EXPECT_FALSE(resolver->open_tab_at(ScreenPoint{0, 1250, 780, 1250, 780}, put)) << "the bare desktop";
    ASSERT_TRUE(resolver->open_tab_at(at, put));
    ASSERT_TRUE(wait_until([&] { return reported(put).has_value(); }, 20s));
    EXPECT_EQ(reported(put)->id, before.id) << "a tab in the window pointed at";
    EXPECT_NE(reported(put)->tab.id, before.tab.id) << "a new tab";
}

TEST_P(BrowserCompanion, AHostilePageGetsClearBoundedAnswers) {
    const std::string page = origin + "/hostile.html";
    start_browser(page);
    std::optional<WindowInfo> window;
    ASSERT_TRUE(wait_until(
        [&] {
            window = window_titled("Hostile TTTT");
            for (const auto& b : link->browsers())
                for (const auto& w : b.windows)
                    if (w.tab.url == page && w.tab.title.rfind("Hostile TTTT", 0) == 0) return window.has_value();
            return false;
        },
        90s))
        << log_of("browser.log").substr(0, 4000);
    for (const auto& b : link->browsers())
        for (const auto& w : b.windows) EXPECT_LE(w.tab.title.size(), 512u);
    struct Case {
        const char* what;
        Spot spot;
        protocol::ContentKind kind;
        std::string title_start, url;
    };
    const std::vector<Case> cases = {
        {"javascript: link", kLink, protocol::ContentKind::url, "Page: Hostile TTTT", page},
        {"data: link", kVideo, protocol::ContentKind::url, "Page: Hostile TTTT", page},
        {"100 MB image", kImage, protocol::ContentKind::url, "Image: big.png", origin + "/big.png"},
        {"churning text", kText, protocol::ContentKind::url, "Page: Hostile TTTT", page},
    };
    for (const Case& c : cases) {
        const auto t0 = Clock::now();
        const auto resolved = resolver->resolve(point_on(*window, c.spot), Purpose::grab);
        EXPECT_LT(Clock::now() - t0, 15s) << c.what;
        ASSERT_TRUE(resolved) << c.what;
        EXPECT_EQ(resolved->kind, c.kind) << c.what;
        // Firefox 153 ESR does not hit-test the broken image while its
        // 100 MB still load: the page is the answer there, as clear and
        // as bounded.
        if (GetParam() == Browser::firefox && c.spot.left == kImage.left && resolved->title.rfind("Page: Hostile", 0) == 0) {
            std::printf("  %s: the page (%s)\n", c.what, resolved->url.substr(0, 80).c_str());
            continue;
        }
        EXPECT_EQ(resolved->title.rfind(c.title_start, 0), 0u) << c.what << ": " << resolved->title.substr(0, 80);
        EXPECT_LE(resolved->title.size(), 520u) << c.what;
        EXPECT_EQ(resolved->url.substr(0, c.url.size()), c.url) << c.what;
        EXPECT_EQ(resolved->url.find("javascript:"), std::string::npos);
        EXPECT_EQ(resolved->url.find("data:"), std::string::npos);
    }
    EXPECT_EQ(link->browsers().size(), 1u) << "the host is still there";
    // The page's tries to reach the extension came to nothing.
    std::this_thread::sleep_for(1s);
    for (const auto& b : link->browsers())
        for (const auto& w : b.windows) {
            EXPECT_EQ(w.tab.title.rfind("Hostile TTTT", 0), 0u) << "the page was answered: " << w.tab.title.substr(0, 40);
            EXPECT_EQ(w.tab.url.find("evil.example"), std::string::npos) << "the page opened a tab";
        }
}

TEST_P(BrowserCompanion, WithoutTheCompanionTheConsoleSaysOnceHowToSetItUp) {
    fs::remove_all(dir.path / "config" / "chromium" / "NativeMessagingHosts");
    fs::remove_all(dir.path / ".mozilla" / "native-messaging-hosts");
    std::ostringstream console;
    WindowFilter filter;
    filter.own_pids.insert(static_cast<int>(::getpid()));
    const BrowserResolver without(desktop, filter, link, &console);
    start_browser(origin + "/index.html");
    ASSERT_TRUE(wait_until([&] { return page_window().has_value(); }, 90s)) << log_of("browser.log").substr(0, 4000);
    const WindowInfo w = *page_window();
    EXPECT_TRUE(link->browsers().empty());
    const ScreenPoint centre{0, w.rect.x + w.rect.width / 2.0, w.rect.y + w.rect.height / 2.0,
                             w.rect.x + w.rect.width / 2.0, w.rect.y + w.rect.height / 2.0};
    EXPECT_FALSE(without.resolve(centre, Purpose::preview));
    EXPECT_EQ(console.str(), "") << "an aim says nothing";
    EXPECT_FALSE(without.resolve(centre, Purpose::grab));
    EXPECT_NE(console.str().find("umf-provider browser install"), std::string::npos) << console.str();
    const std::string once = console.str();
    EXPECT_FALSE(without.resolve(centre, Purpose::grab));
    EXPECT_EQ(console.str(), once) << "said once";
}

// A private window of the same browser over a normal one showing the same
// page (Chromium puts it exactly there: the report cannot tell them apart).
TEST_P(BrowserCompanion, APrivateWindowGivesNothingOfItsOwn) {
    const std::string page = origin + "/index.html", secret = origin + "/index.html?secret=1";
    open_page(page);
    const WindowInfo normal = *page_window();
    // A private window of the same browser, on top of the normal one.
    open_private_window(normal, secret);
    std::optional<WindowInfo> incognito;
    ASSERT_TRUE(wait_until(
        [&] {
            for (const auto& w : desktop->windows())
                if (w.id != normal.id && w.pid == normal.pid && w.title.find("Companion") != std::string::npos) incognito = w;
            return incognito.has_value();
        },
        30s));
    // Exactly over the normal one (Chromium puts it there; Firefox a little aside).
    run({"xdotool", "windowmove", "--sync", std::to_string(incognito->id), std::to_string(normal.rect.x),
         std::to_string(normal.rect.y)},
        env);
    std::this_thread::sleep_for(2s);  // what the extension would report, it has reported by now
    for (const auto& w : desktop->windows())
        if (w.id == incognito->id) incognito = w;
    for (const auto& b : link->browsers())
        for (const auto& w : b.windows) EXPECT_EQ(w.tab.url.find("secret"), std::string::npos) << w.tab.url;
    const double cx = incognito->rect.x + incognito->rect.width / 2.0, cy = incognito->rect.y + incognito->rect.height / 2.0;
    const auto over_private = desktop->window_at(cx, cy);
    ASSERT_TRUE(over_private);
    if (over_private->id == incognito->id) {
        const auto resolved = resolver->resolve(ScreenPoint{0, cx, cy, cx, cy}, Purpose::grab);
        EXPECT_FALSE(resolved) << "a private window gave " << resolved->url;
        EXPECT_FALSE(resolver->open_tab_at(ScreenPoint{0, cx, cy, cx, cy}, origin + "/index.html?put=1"));
    } else {
        ADD_FAILURE() << "the private window is not on top at its centre";
    }
}

INSTANTIATE_TEST_SUITE_P(RealBrowsers, BrowserCompanion, ::testing::Values(Browser::chromium, Browser::firefox),
                         [](const auto& info) { return info.param == Browser::chromium ? "Chromium" : "Firefox"; });

}  // namespace
}  // namespace umf::provider::browser_test
#endif
