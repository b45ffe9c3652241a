// The browser companion's test bench with the real browsers: Xvfb and
// openbox, Debian's Chromium (the extension loaded unpacked) or Firefox ESR
// (the extension in a fresh profile, unsigned add-ons allowed as ESR
// permits), the host they start (umf-browser-host, set up by `umf-provider
// browser install`), the provider's browser link and resolver over the real
// X11 desktop, and pages served on 127.0.0.1. Tests skip when Xvfb, openbox,
// python3, xdotool or the browser are missing.
#pragma once

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "provider/browser/browser_link.hpp"
#include "provider/browser/browser_resolver.hpp"
#include "provider/browser/host_manifests.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::provider::browser_test {


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

inline std::string page_html() {
    auto fixed = [](const Spot& s) {
        return "position:fixed;left:" + std::to_string(s.left) + "px;bottom:" + std::to_string(s.bottom) +
               "px;width:" + std::to_string(s.width) + "px;height:" + std::to_string(s.height) + "px;";
    };
    // The title is the page's only once passage 15 sits under kText: a test
    // waits for it (page_window, reported) before it points.
    std::string html = "<!doctype html><html><head><meta charset=utf-8><title>Loading</title><style>"
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
    // Passage 15 under kText's centre: the long text scrolled to its middle,
    // and again whenever the viewport's height changes (Chromium's infobar
    // for --no-sandbox may come after the page has loaded and would move the
    // text a passage down under the point).
    html += "<script>const place=()=>{const p=document.getElementById('p15');"
            "scrollTo(0,p.offsetTop+50-(innerHeight-" +
            std::to_string(kText.bottom + kText.height / 2) +
            "));};addEventListener('resize',place);"
            "addEventListener('load',()=>{place();document.title='Companion test page';});</script>\n";
    return html + "</body></html>\n";
}

// A page that is no friend: a title of 1 MB, a javascript: and a data: link,
// an image of 100 MB, its document rewritten every few milliseconds.
inline std::string hostile_html() {
    auto fixed = [](const Spot& s) {
        return "position:fixed;left:" + std::to_string(s.left) + "px;bottom:" + std::to_string(s.bottom) +
               "px;width:" + std::to_string(s.width) + "px;height:" + std::to_string(s.height) + "px;display:block;";
    };
    return "<!doctype html><html><head><meta charset=utf-8><title>x</title></head><body>"
           "<a href=\"javascript:alert(1)\" style=\"" + fixed(kLink) + "\">Run me</a>"
           "<img src=\"big.png\" style=\"" + fixed(kImage) + "\">"
           "<a href=\"data:text/html,<h1>hi</h1>\" style=\"" + fixed(kVideo) + "\">Data</a>"
           "<div id=churn style=\"" + fixed(kText) + "\"></div>"
           // It also tries to reach the extension (and through it the host):
           // were it answered, its title would say OPEN.
           "<script>document.title='Hostile '+'T'.repeat(1<<20);let n=0;"
           "try{const r=window.chrome&&chrome.runtime;if(r&&r.sendMessage)r.sendMessage('" +
           std::string(kChromiumExtensionId) +
           "',{type:'open_tab',url:'https://evil.example/'},(a)=>{if(a)document.title='Hostile OPEN';});"
           "if(r&&r.connect){const p=r.connect('" + std::string(kChromiumExtensionId) +
           "');p.onMessage.addListener(()=>{document.title='Hostile OPEN';});p.postMessage({type:'hello'});}"
           "}catch(e){}window.postMessage({type:'open_tab',url:'https://evil.example/'},'*');"
           "setInterval(()=>{const d=document.getElementById('churn');d.innerHTML='';"
           "for(let i=0;i<50;++i){const s=document.createElement('span');s.textContent='churn '+(n++)+' ';d.appendChild(s);}},4);"
           "</script></body></html>\n";
}

// A solid PNG (stored, not compressed: no zlib needed to make one).
inline std::string tiny_png() {
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

    Process::Options options(const std::string& log) const { return logged_in(dir.path, env, log); }
    std::string log_of(const std::string& log) const { return read_text(dir.path / log); }

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

}  // namespace umf::provider::browser_test
