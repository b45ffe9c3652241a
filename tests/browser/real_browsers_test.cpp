// The browser companion with the real browsers: Xvfb and openbox, Debian's
// Chromium (the extension loaded unpacked) and Firefox ESR (the extension in
// a fresh profile, unsigned add-ons allowed as ESR permits), the host they start
// (umf-browser-host, set up by `umf-provider browser install`), the
// provider's browser link and resolver over the real X11 desktop. A local
// page (served on 127.0.0.1) holds a link, an image, a video and a long text
// scrolled to its middle; grabs and aims at each must give the right kind,
// title and URL; a URL put there opens as a tab in that window; a private
// window gives nothing of its own. Skipped when Xvfb, openbox, python3 or
// the browser are missing.
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "browser/browser_link.hpp"
#include "browser/browser_resolver.hpp"
#include "browser/host_manifests.hpp"
#include "desktop/x11/x11_desktop.hpp"
#include "support/temp_dir.hpp"
#include "support/x11_session.hpp"

namespace umf::provider {
namespace {

using json = nlohmann::json;
using namespace umf::test;
namespace fs = std::filesystem;

// Everything on the page is placed from the viewport's bottom-left corner,
// which is the window's (Chromium draws nothing below or beside the page;
// openbox's frame adds a pixel or few), so screen points follow from the
// window's rectangle alone.
constexpr int kWindowX = 60, kWindowY = 40, kWindowW = 1000, kWindowH = 720;
struct Spot {
    int left, bottom, width, height;
};
constexpr Spot kLink{20, 470, 400, 70}, kImage{20, 260, 200, 150}, kVideo{300, 260, 240, 150}, kText{20, 100, 900, 100};

std::string page_html() {
    auto fixed = [](const Spot& s) {
        return "position:fixed;left:" + std::to_string(s.left) + "px;bottom:" + std::to_string(s.bottom) +
               "px;width:" + std::to_string(s.width) + "px;height:" + std::to_string(s.height) + "px;";
    };
    std::string html = "<!doctype html><html><head><meta charset=utf-8><title>Companion test page</title><style>"
                       "body{margin:0;font:18px sans-serif} p{height:100px;margin:0;overflow:hidden;white-space:nowrap}"
                       "</style></head><body>\n";
    for (int i = 1; i <= 30; ++i)
        html += "<p id=p" + std::to_string(i) + ">Passage number " + std::to_string(i) +
                " begins here and goes on about the river, the hills and the slow evening light over field " +
                std::to_string(i) + "</p>\n";
    html += "<a id=link href=\"https://example.org/release-notes\" style=\"" + fixed(kLink) +
            "display:block;background:#fff;font-size:40px\">Release notes</a>\n";
    html += "<img id=image src=\"chart.png\" alt=\"A chart\" style=\"" + fixed(kImage) + "\">\n";
    html += "<video id=video src=\"clip.webm\" style=\"" + fixed(kVideo) + "background:#000\"></video>\n";
    // Passage 15 under kText's centre: the long text scrolled to its middle.
    html += "<script>addEventListener('load',()=>{const p=document.getElementById('p15');"
            "scrollTo(0,p.offsetTop+50-(innerHeight-" +
            std::to_string(kText.bottom + kText.height / 2) + "));document.title='Companion test page';});</script>\n";
    return html + "</body></html>\n";
}

// A page that is no friend: a title of 1 MB, a javascript: and a data: link,
// an image of 100 MB, its document rewritten every few milliseconds.
std::string hostile_html() {
    auto fixed = [](const Spot& s) {
        return "position:fixed;left:" + std::to_string(s.left) + "px;bottom:" + std::to_string(s.bottom) +
               "px;width:" + std::to_string(s.width) + "px;height:" + std::to_string(s.height) + "px;display:block;";
    };
    return "<!doctype html><html><head><meta charset=utf-8><title>x</title></head><body>"
           "<a href=\"javascript:alert(1)\" style=\"" + fixed(kLink) + "\">Run me</a>"
           "<img src=\"big.png\" style=\"" + fixed(kImage) + "\">"
           "<a href=\"data:text/html,<h1>hi</h1>\" style=\"" + fixed(kVideo) + "\">Data</a>"
           "<div id=churn style=\"" + fixed(kText) + "\"></div>"
           "<script>document.title='Hostile '+'T'.repeat(1<<20);let n=0;"
           "setInterval(()=>{const d=document.getElementById('churn');d.innerHTML='';"
           "for(let i=0;i<50;++i){const s=document.createElement('span');s.textContent='churn '+(n++)+' ';d.appendChild(s);}},4);"
           "</script></body></html>\n";
}

// A solid PNG (stored, not compressed: no zlib needed to make one).
std::string tiny_png() {
    static const unsigned char png[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00,
        0x0c, 0x49, 0x44, 0x41, 0x54, 0x08, 0xd7, 0x63, 0xf8, 0xcf, 0xc0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0x18,
        0xdd, 0x8d, 0xb0, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    return std::string(reinterpret_cast<const char*>(png), sizeof png);
}

enum class Browser { chromium, firefox };

class BrowserCompanion : public ::testing::TestWithParam<Browser> {
protected:
    TempDir dir;
    std::vector<std::string> env;
    std::unique_ptr<Process> xvfb, openbox, http, browser;
    std::shared_ptr<const X11Desktop> desktop;
    std::shared_ptr<BrowserLink> link = std::make_shared<BrowserLink>();
    std::unique_ptr<BrowserResolver> resolver;
    std::string origin;  // http://127.0.0.1:PORT

    void SetUp() override {
        for (const char* program : {"Xvfb", "openbox", "python3", "xdotool", GetParam() == Browser::chromium ? "chromium" : "firefox-esr"})
            if (!find_program(program))
                GTEST_SKIP() << program << " is not installed (scripts/install-deps.sh installs it)";
        const fs::path runtime = dir.path / "run";
        fs::create_directories(runtime);
        ::chmod(runtime.c_str(), 0700);
        auto server = start_xvfb(dir.path / "xvfb.log", "1280x800x24");
        xvfb = std::move(server.process);
        env = environment_with({{"DISPLAY", server.display},
                                {"HOME", dir.path.string()},
                                {"XDG_CONFIG_HOME", (dir.path / "config").string()},
                                {"XDG_CACHE_HOME", (dir.path / "cache").string()},
                                {"XDG_RUNTIME_DIR", runtime.string()}});
        desktop = std::make_shared<const X11Desktop>(server.display);
        openbox = start_openbox(options("openbox.log"), dir.path / "openbox-ready");
        serve_page();
        const std::string install = run({UMF_PROVIDER_TOOL, "browser", "install", "--host", UMF_BROWSER_HOST_TOOL}, env);
        ASSERT_NE(install.find("Chromium: " + (dir.path / "config/chromium/NativeMessagingHosts").string()),
                  std::string::npos)
            << install;
        link->listen(runtime / "umf" / "browser-47990.sock");
        WindowFilter filter;
        filter.own_pids.insert(static_cast<int>(::getpid()));
        BrowserResolverOptions o;
        o.aim_timeout = std::chrono::milliseconds(300);  // a loaded test machine; the default is measured apart
        resolver = std::make_unique<BrowserResolver>(desktop, filter, link, nullptr, o);
    }

    void TearDown() override {
        resolver.reset();
        browser.reset();
        http.reset();
        desktop.reset();  // before the X server goes
        openbox.reset();
        xvfb.reset();
    }

    Process::Options options(const std::string& log) const {
        Process::Options o;
        o.cwd = dir.path;
        o.env = env;
        o.log = dir.path / log;
        return o;
    }

    std::string log_of(const std::string& log) const {
        std::ifstream in(dir.path / log);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    void serve_page() {
        const fs::path www = dir.path / "www";
        fs::create_directories(www);
        std::ofstream(www / "index.html") << page_html();
        std::ofstream(www / "chart.png", std::ios::binary) << tiny_png();
        std::ofstream(www / "hostile.html") << hostile_html();
        fs::resize_file((std::ofstream(www / "big.png"), www / "big.png"), 100ull * 1024 * 1024);  // sparse
        std::ofstream(www / "photo.html") << "<!doctype html><title>Companion test page</title><body style=margin:0>"
                                             "<img src=photo.jpg style=\"position:fixed;left:" << kImage.left
                                          << "px;bottom:" << kImage.bottom << "px;width:" << kImage.width
                                          << "px;height:" << kImage.height << "px;display:block\">";
        std::string photo(5 * 1024 * 1024, '\0');
        for (std::size_t i = 0; i < photo.size(); ++i) photo[i] = static_cast<char>((i * 2654435761u) >> 13);
        std::ofstream(www / "photo.jpg", std::ios::binary) << photo;
        auto o = options("http.log");
        o.cwd = www;
        o.env.push_back("PYTHONUNBUFFERED=1");
        http = std::make_unique<Process>(
            std::vector<std::string>{"python3", "-m", "http.server", "0", "--bind", "127.0.0.1"}, o);
        std::smatch m;
        std::string text;
        ASSERT_TRUE(wait_until(
            [&] {
                text = log_of("http.log");
                return std::regex_search(text, m, std::regex("port ([0-9]+)"));
            },
            10s))
            << text;
        origin = "http://127.0.0.1:" + m[1].str();
    }

    void start_browser(const std::string& url) {
        if (GetParam() == Browser::firefox) return start_firefox(url);
        std::vector<std::string> argv = {"chromium",
                                         "--no-first-run",
                                         "--no-default-browser-check",
                                         "--password-store=basic",
                                         "--disable-gpu",
                                         "--force-device-scale-factor=1",
                                         "--disable-features=DisableLoadExtensionCommandLineSwitch",
                                         "--load-extension=" + std::string(UMF_BROWSER_EXTENSION_DIR),
                                         "--window-position=" + std::to_string(kWindowX) + "," + std::to_string(kWindowY),
                                         "--window-size=" + std::to_string(kWindowW) + "," + std::to_string(kWindowH)};
        if (::getuid() == 0) argv.insert(argv.begin() + 1, "--no-sandbox");
        argv.push_back(url);
        browser = std::make_unique<Process>(argv, options("browser.log"));
    }

    // A profile of the test's own with the extension installed in it, as
    // an unsigned add-on (ESR honours xpinstall.signatures.required).
    void start_firefox(const std::string& url) {
        const fs::path profile = dir.path / "firefox-profile";
        fs::create_directories(profile / "extensions");
        const std::string xpi = (profile / "extensions" / (std::string(kFirefoxExtensionId) + ".xpi")).string();
        run({"python3", "-c",
             "import os,sys,zipfile\nz=zipfile.ZipFile(sys.argv[2],'w')\n"
             "for f in sorted(os.listdir(sys.argv[1])): z.write(os.path.join(sys.argv[1],f),f)\nz.close()",
             UMF_BROWSER_EXTENSION_DIR, xpi},
            env);
        std::ofstream prefs(profile / "user.js");
        for (const char* pref :
             {"\"xpinstall.signatures.required\", false", "\"extensions.autoDisableScopes\", 0",
              "\"extensions.enabledScopes\", 15", "\"browser.shell.checkDefaultBrowser\", false",
              "\"browser.startup.homepage_override.mstone\", \"ignore\"",
              "\"datareporting.policy.dataSubmissionEnabled\", false", "\"browser.aboutwelcome.enabled\", false",
              "\"toolkit.telemetry.reportingpolicy.firstRun\", false"})
            prefs << "user_pref(" << pref << ");\n";
        prefs.close();
        browser = std::make_unique<Process>(
            std::vector<std::string>{"firefox-esr", "--no-remote", "--profile", profile.string(), "--width",
                                     std::to_string(kWindowW), "--height", std::to_string(kWindowH), url},
            options("browser.log"));
    }

    std::optional<WindowInfo> window_titled(const std::string& title) const {
        for (const auto& w : desktop->windows())
            if (w.title.rfind(title, 0) == 0) return w;
        return std::nullopt;
    }

    // The browser's report of the window showing `url`, once it came.
    std::optional<BrowserWindow> reported(const std::string& url) const {
        for (const auto& b : link->browsers())
            for (const auto& w : b.windows)
                if (w.tab.url == url && w.tab.title == "Companion test page") return w;
        return std::nullopt;
    }

    std::optional<WindowInfo> page_window() const { return window_titled("Companion test page"); }

    // Started on the page and reported with it.
    void open_page(const std::string& page) {
        start_browser(page);
        ASSERT_TRUE(wait_until([&] { return reported(page).has_value() && page_window().has_value(); }, 90s))
            << "the browser said: " << log_of("browser.log").substr(0, 4000) << "\nbrowsers: " << link->browsers().size();
    }

    // As a person does: Chromium hands --incognito URL to the running
    // browser; in Firefox, Ctrl+Shift+P, then the URL typed into the new
    // window's address bar (its command line would need D-Bus here).
    void open_private_window(const WindowInfo& normal, const std::string& url) {
        if (GetParam() == Browser::chromium) {
            std::vector<std::string> argv = {"chromium", "--incognito", url};
            if (::getuid() == 0) argv.insert(argv.begin() + 1, "--no-sandbox");
            run(argv, env);
            return;
        }
        run({"xdotool", "windowactivate", "--sync", std::to_string(normal.id), "key", "ctrl+shift+p"}, env);
        ASSERT_TRUE(wait_until([&] { return window_titled("Private Browsing").has_value() ||
                                            desktop->windows().size() > 1; }, 20s));
        std::this_thread::sleep_for(1s);
        run({"xdotool", "type", "--delay", "10", url}, env);
        run({"xdotool", "key", "Return"}, env);
    }

    ScreenPoint point_on(const WindowInfo& w, const Spot& s) const {
        const double x = w.rect.x + s.left + s.width / 2.0;
        const double y = w.rect.y + w.rect.height - s.bottom - s.height / 2.0;
        return ScreenPoint{0, x, y, x, y};
    }
};

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
        EXPECT_EQ(resolved->title.rfind(c.title_start, 0), 0u) << c.what << ": " << resolved->title.substr(0, 80);
        EXPECT_LE(resolved->title.size(), 520u) << c.what;
        EXPECT_EQ(resolved->url.substr(0, c.url.size()), c.url) << c.what;
        EXPECT_EQ(resolved->url.find("javascript:"), std::string::npos);
        EXPECT_EQ(resolved->url.find("data:"), std::string::npos);
    }
    EXPECT_EQ(link->browsers().size(), 1u) << "the host is still there";
}

// The whole way, as a phone goes: a real provider serving the desktop (its
// own browser link), the browser's host connected to it, `browser status`,
// and aims and grabs over the HTTPS transport at field points over the
// page's link and image; the image's download brings its bytes.
TEST_P(BrowserCompanion, TheProviderGivesAPhoneWhatTheBrowserShows) {
    resolver.reset();
    link.reset();  // the test's own link goes, so the host finds the provider's
    auto provider = std::make_unique<Process>(
        std::vector<std::string>{UMF_PROVIDER_TOOL, "serve", "--desktop", "x11", "--port", "0", "--no-overlay", "--no-qr",
                                 "--config-dir", (dir.path / "provider-config").string(), "--puts", "never"},
        options("provider.log"));
    std::smatch m;
    std::string said;
    ASSERT_TRUE(wait_until(
        [&] {
            said = log_of("provider.log");
            return std::regex_search(said, m, std::regex("pairing URL: https://[^:]+:([0-9]+)/#t=([A-Za-z0-9_-]+)"));
        },
        30s))
        << said;
    const std::string port = m[1].str(), token = m[2].str(), base = "https://127.0.0.1:" + port;
    const std::string page = origin + "/index.html";
    start_browser(page);
    std::string status;
    ASSERT_TRUE(wait_until(
        [&] {
            status = run({UMF_PROVIDER_TOOL, "browser", "status", "--port", port}, env);
            return status.find(page) != std::string::npos && page_window().has_value();
        },
        90s))
        << status << log_of("browser.log").substr(0, 3000);
    EXPECT_NE(status.find(GetParam() == Browser::chromium ? "chromium" : "firefox"), std::string::npos) << status;
    EXPECT_NE(status.find("Companion test page"), std::string::npos) << status;

    auto post = [&](const std::string& path, const json& body) {
        return json::parse(run({"curl", "-sk", "--max-time", "20", "-H", "Content-Type: application/json", "--data",
                                body.dump(), base + path},
                               env, 30s));
    };
    const json hello = post("/api/hello", {{"type", "hello"}, {"v", 1}, {"id", 1}, {"token", token}, {"client", "test"}});
    ASSERT_TRUE(hello.contains("session")) << hello.dump();
    const json screen = hello["messages"][0]["field"]["screens"][0];
    const std::string session = "/api/session/" + hello["session"].get<std::string>();
    // The field point over a screen pixel: each screen's region [u0, v0,
    // u1, v1] spans its pixels.
    auto field_point = [&](const ScreenPoint& p) {
        const json& r = screen["region"];
        const json& px = screen["pixels"];
        return json{r[0].get<double>() + p.x / px[0].get<double>() * (r[2].get<double>() - r[0].get<double>()),
                    r[1].get<double>() + p.y / px[1].get<double>() * (r[3].get<double>() - r[1].get<double>())};
    };
    const WindowInfo window = *page_window();
    // An aim waits little for the page (its title may say "Page: ..." while
    // a browser runs its first script in the tab); the next aims, a few a
    // second, name the link.
    json aim;
    for (int i = 0; i < 10; ++i) {
        aim = post(session, {{"type", "aim"}, {"v", 1}, {"id", 2 + i}, {"point", field_point(point_on(window, kLink))},
                             {"confidence", 0.9}});
        ASSERT_EQ(aim["messages"][0]["type"], "target") << aim.dump();
        if (aim["messages"][0]["title"] == "Link: Release notes") break;
        EXPECT_EQ(aim["messages"][0]["title"], "Page: Companion test page");
        std::this_thread::sleep_for(200ms);
    }
    EXPECT_EQ(aim["messages"][0]["title"], "Link: Release notes");
    const json link_grab =
        post(session, {{"type", "grab"}, {"v", 1}, {"id", "g1"}, {"point", field_point(point_on(window, kLink))}});
    ASSERT_EQ(link_grab["messages"][0]["type"], "content") << link_grab.dump();
    EXPECT_EQ(link_grab["messages"][0]["kind"], "url");
    EXPECT_EQ(link_grab["messages"][0]["url"], "https://example.org/release-notes");
    const json image_grab =
        post(session, {{"type", "grab"}, {"v", 1}, {"id", "g2"}, {"point", field_point(point_on(window, kImage))}});
    const json& content = image_grab["messages"][0];
    ASSERT_EQ(content["type"], "content") << image_grab.dump();
    EXPECT_EQ(content["kind"], "file");
    EXPECT_EQ(content["title"], "Image: chart.png");
    EXPECT_EQ(content["name"], "chart.png");
    EXPECT_EQ(content["size"], tiny_png().size());
    const std::string downloaded =
        run({"curl", "-sk", "--max-time", "20", base + content["download"].get<std::string>()}, env, 30s);
    EXPECT_EQ(downloaded, tiny_png());
    provider.reset();
}

// Without the companion set up, a grab on a browser window gives what it
// gave before (the snapshot resolver's picture), and the console says once
// how to set the companion up.
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

// Not a test: the resolver's time for a browser window, which an aim waits
// for before the phone shows the title (docs/BENCHMARKS.md). Run with
// --gtest_also_run_disabled_tests --gtest_filter='*BrowserCompanion.DISABLED_ResolveTime*'
TEST_P(BrowserCompanion, DISABLED_ResolveTime) {
    const std::string page = origin + "/index.html";
    open_page(page);
    const WindowInfo window = *page_window();
    for (const auto& [what, spot] : {std::pair{"link", kLink}, std::pair{"passage", kText}}) {
        for (const Purpose purpose : {Purpose::preview, Purpose::grab}) {
            std::vector<double> ms;
            for (int i = 0; i < 500; ++i) {
                const auto t0 = Clock::now();
                const auto resolved = resolver->resolve(point_on(window, spot), purpose);
                ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
                ASSERT_TRUE(resolved);
            }
            std::sort(ms.begin(), ms.end());
            std::printf("%-8s %-5s 500 resolves: p50 %.2f ms, p99 %.2f ms, max %.2f ms\n", what,
                        purpose == Purpose::grab ? "grab" : "aim", ms[249], ms[494], ms.back());
        }
    }
    // A grab of a 5 MB image: its bytes through the browser, the host and the link.
    const std::string photo = origin + "/photo.html";
    ASSERT_TRUE(resolver->open_tab_at(point_on(window, kText), photo));
    ASSERT_TRUE(wait_until([&] { return reported(photo).has_value(); }, 20s));
    std::this_thread::sleep_for(1s);
    std::vector<double> ms;
    for (int i = 0; i < 20; ++i) {
        const auto t0 = Clock::now();
        const auto resolved = resolver->resolve(point_on(*page_window(), kImage), Purpose::grab);
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        ASSERT_TRUE(resolved && resolved->bytes);
        ASSERT_EQ(resolved->bytes->size(), 5u * 1024 * 1024);
    }
    std::sort(ms.begin(), ms.end());
    std::printf("5 MB image grab, 20 resolves: p50 %.1f ms, max %.1f ms\n", ms[9], ms.back());
}

INSTANTIATE_TEST_SUITE_P(RealBrowsers, BrowserCompanion, ::testing::Values(Browser::chromium, Browser::firefox),
                         [](const auto& info) { return info.param == Browser::chromium ? "Chromium" : "Firefox"; });

}  // namespace
}  // namespace umf::provider
#endif
