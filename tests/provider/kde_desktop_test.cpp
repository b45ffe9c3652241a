// The KDE Plasma backend (desktop/kde): its scripts and answers on their
// own, the scripts' logic in node with a fake KWin 5.27 and KWin 6
// workspace, and the backend against a real kwin_wayland --virtual with
// Xwayland, an X11 client (xterm) and a native Wayland client
// (weston-simple-shm; foot dies of a division by zero on KWin's virtual
// output, which has no physical size).
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <QImage>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <thread>

#include "provider/desktop/kde/kde_desktop.hpp"
#include "provider/desktop/kde/kwin_screenshot.hpp"
#include "provider/desktop/kde/kwin_scripts.hpp"
#include "provider/desktop/kde/wayland_outputs.hpp"
#include "tests/provider/gui_test_app.hpp"
#include "tests/support/kwin_session.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using namespace umf::provider;
using namespace umf::test;

// ---- Against a real KWin ---------------------------------------------------

// One fixture for the suite (gtest wants one per suite); only the tests that
// need KWin start it, and skip where it cannot run.
#define UMF_NEEDS_KWIN()                                                                                    \
    do {                                                                                                    \
        if (const auto missing = kwin_missing()) GTEST_SKIP() << *missing;                                \
        for (const char* program : {"xterm", "weston-simple-shm"})                                          \
            if (!find_program(program))                                                                     \
                GTEST_SKIP() << program << " is not installed (Debian: apt-get install -y xterm weston)";  \
        ensure_gui_application();                                                                           \
        session = std::make_unique<KWinSession>(start_kwin());                                              \
    } while (false)

struct KdeDesktop : ::testing::Test {
    std::unique_ptr<Desktop> desktop() {
        KdeDesktopOptions options;
        options.bus_address = session->bus_address;
        options.wayland_display = (session->runtime / session->wayland_display).string();
        options.script_dir = session->dir->path / "scripts";
        return make_kde_desktop(options);
    }
    std::unique_ptr<Process> start(const std::vector<std::string>& argv, const std::string& log) {
        return session->start_client(argv, log);
    }
    std::unique_ptr<KWinSession> session;
};

TEST_F(KdeDesktop, TheWindowListIsReadAndTheTopMostUnskippedWindowAtThePointWins) {
    const auto parsed = parse_window_list(
        R"([{"uuid":"{a}","stacking":0,"x":0,"y":0,"width":800,"height":600,"caption":"below","resourceClass":"xterm",)"
        R"("resourceName":"xterm","pid":10,"x11":true},)"
        R"({"uuid":"{b}","stacking":3,"x":100.4,"y":100.6,"width":200,"height":200,"caption":"Ünïcode \"top\"",)"
        R"("resourceClass":"org.app","resourceName":"app","pid":20,"x11":false}])");
    ASSERT_TRUE(parsed);
    ASSERT_EQ(parsed->size(), 2u);
    EXPECT_EQ((*parsed)[1].rect, (WindowRect{100, 101, 200, 200}));
    EXPECT_EQ((*parsed)[1].caption, "Ünïcode \"top\"");
    const std::vector<DesktopOutput> outputs{{"A", {0, 0, 150, 1080}, 1.0}, {"B", {150, 0, 1000, 1080}, 1.0}};

    const auto top = window_at_point(*parsed, 150, 150, {}, outputs);
    ASSERT_TRUE(top);
    EXPECT_EQ(top->title, "Ünïcode \"top\"");
    EXPECT_EQ(top->wm_class, "org.app");
    EXPECT_EQ(top->instance, "");  // Wayland: no instance
    EXPECT_EQ(top->pid, 20);
    EXPECT_EQ(top->output, "B");
    EXPECT_EQ(top->id, window_id("{b}"));

    WindowFilter own;
    own.own_pids = {20};
    const auto below = window_at_point(*parsed, 150, 150, own, outputs);
    ASSERT_TRUE(below);
    EXPECT_EQ(below->title, "below");
    EXPECT_EQ(below->instance, "xterm");
    WindowFilter classes;
    classes.skip_classes = {"xterm", "org.app"};
    EXPECT_FALSE(window_at_point(*parsed, 150, 150, classes, outputs));
    EXPECT_FALSE(window_at_point(*parsed, 900, 900, {}, outputs));

    EXPECT_FALSE(parse_window_list("not json"));
    EXPECT_FALSE(parse_window_list(R"({"uuid":"x"})"));
    EXPECT_FALSE(parse_window_list(R"([{"caption":"no uuid"}])"));
    EXPECT_TRUE(parse_window_list("[]"));
}

TEST_F(KdeDesktop, TextBecomesASafeJavaScriptString) {
    EXPECT_EQ(js_string("a\"b\\c"), R"("a\"b\\c")");
    EXPECT_EQ(js_string("line\nend"), R"("line\u000aend")");
    EXPECT_EQ(js_string("x\xe2\x80\xa8y"), R"("x\u2028y")");
}

TEST_F(KdeDesktop, KWinsRawScreenshotsBecomeOpaqueRgb) {
    // 2x1, ARGB32 premultiplied (KWin's area shots), a half transparent red.
    QImage image(2, 1, QImage::Format_ARGB32_Premultiplied);
    image.setPixel(0, 0, qRgba(0x10, 0x20, 0x30, 0xff));
    image.setPixel(1, 0, 0x80800000u);
    const QByteArray bytes(reinterpret_cast<const char*>(image.constBits()), image.sizeInBytes());
    QVariantMap layout{{"type", "raw"}, {"format", uint(QImage::Format_ARGB32_Premultiplied)}, {"width", 2u},
                       {"height", 1u}, {"stride", uint(image.bytesPerLine())}};
    const Capture capture = capture_from_raw(layout, bytes);
    ASSERT_EQ(capture.pixels.size(), 2u);
    EXPECT_EQ(capture.pixels[0], 0xff102030u);
    EXPECT_EQ(capture.pixels[1], 0xff800000u);

    // RGBA8888 byte order.
    const QImage rgba = image.convertToFormat(QImage::Format_RGBA8888);
    layout["format"] = uint(QImage::Format_RGBA8888);
    layout["stride"] = uint(rgba.bytesPerLine());
    EXPECT_EQ(capture_from_raw(layout, QByteArray(reinterpret_cast<const char*>(rgba.constBits()), rgba.sizeInBytes()))
                  .pixels[0],
              0xff102030u);

    EXPECT_THROW(capture_from_raw(layout, bytes.left(3)), DesktopError);
    layout["type"] = "png";
    EXPECT_THROW(capture_from_raw(layout, bytes), DesktopError);
}

// `umf-provider kde install` writes the entry KWin looks for, naming the
// program's own path, where KWin's application lookup finds it.
TEST_F(KdeDesktop, InstallWritesTheDesktopEntryForThisProgram) {
    TempDir dir;
    const auto result = umf::test::run_command("XDG_DATA_HOME=" + (dir.path / "data").string() + " " +
                                          std::string(UMF_PROVIDER_TOOL) + " kde install 2>&1");
    ASSERT_EQ(result.exit_code, 0) << result.out;
    std::ifstream in(dir.path / "data" / "applications" / "umf-provider.desktop");
    const std::string entry{std::istreambuf_iterator<char>(in), {}};
    const std::string program = std::filesystem::canonical(UMF_PROVIDER_TOOL).string();
    EXPECT_NE(entry.find("\nExec=" + program + "\n"), std::string::npos) << entry;
    EXPECT_NE(entry.find("X-KDE-DBUS-Restricted-Interfaces=org.kde.KWin.ScreenShot2"), std::string::npos);
    EXPECT_NE(umf::test::run_command(std::string(UMF_PROVIDER_TOOL) + " kde uninstall 2>&1").exit_code, 0);
}

// The list and move scripts against a fake KWin in node: the 5.27 API
// (clientList, integer desktops) and the KWin 6 one (windowList, desktop
// objects), with minimised, dock and other-desktop windows left out.
std::string run_in_node(const std::string& fake_workspace, const std::string& script) {
    TempDir dir;
    std::ofstream(dir.path / "s.js") << "var answers = [];\nfunction umfAnswer(t) { answers.push(t); }\n"
                                     << fake_workspace << "\n" << script
                                     << "\nconsole.log(answers.join('\\n'));\n"
                                     << "if (typeof moved !== 'undefined') console.log(JSON.stringify(moved.frameGeometry));\n";
    return run({"node", (dir.path / "s.js").string()}, environment_with({}), 10s);
}

TEST_F(KdeDesktop, TheScriptsSpeakKWin5AndKWin6) {
    if (!find_program("node")) GTEST_SKIP() << "node is not installed (Debian: apt-get install -y nodejs)";
    const std::string windows = R"(
function win(id, extra) {
  var w = {internalId: "{" + id + "}", stackingOrder: 1, frameGeometry: {x: 1, y: 2, width: 30, height: 40},
           caption: id, resourceClass: "c", resourceName: "n", pid: 7, normalWindow: true, dialog: false,
           minimized: false, deleted: false, onAllDesktops: false};
  for (var k in extra) w[k] = extra[k];
  return w;
}
)";
    const std::string kwin5 = windows + R"(
var list = [win("shown", {desktop: 1, windowId: 4194316}), win("min", {desktop: 1, minimized: true}),
            win("dock", {desktop: 1, normalWindow: false}), win("other", {desktop: 2}),
            win("all", {desktop: -1}), win("dialog", {desktop: 1, normalWindow: false, dialog: true})];
var workspace = {currentDesktop: 1, clientList: function () { return list; }};
var moved = list[0];
)";
    const std::string kwin6 = windows + R"(
var d1 = {id: "d1"}, d2 = {id: "d2"};
var list = [win("shown", {desktops: [d1]}), win("min", {desktops: [d1], minimized: true}),
            win("dock", {desktops: [d1], normalWindow: false}), win("other", {desktops: [d2]}),
            win("all", {desktops: [], onAllDesktops: true}), win("dialog", {desktops: [d1], dialog: true})];
var workspace = {currentDesktop: d1, windowList: function () { return list; }};
var moved = list[0];
)";
    for (const auto& fake : {kwin5, kwin6}) {
        const std::string out = run_in_node(fake, list_windows_script());
        const auto parsed = parse_window_list(out.substr(0, out.find('\n')));
        ASSERT_TRUE(parsed) << out;
        std::vector<std::string> captions;
        for (const auto& w : *parsed) captions.push_back(w.caption);
        EXPECT_EQ(captions, (std::vector<std::string>{"shown", "all", "dialog"})) << out;
        EXPECT_EQ((*parsed)[0].rect, (WindowRect{1, 2, 30, 40}));
        const std::string move = run_in_node(fake, move_window_script("{shown}", {5, 6, 70, 80}));
        EXPECT_EQ(move, "moved\n{\"x\":5,\"y\":6,\"width\":70,\"height\":80}\n");
        EXPECT_EQ(run_in_node(fake, move_window_script("{gone}", {5, 6, 70, 80})).substr(0, 8), "missing\n");
    }
}

TEST_F(KdeDesktop, KdeDesktopFindsX11AndWaylandWindowsWithTitleClassAndPid) {
    UMF_NEEDS_KWIN();
    auto xterm = start({"xterm", "-title", "umf-xterm", "-geometry", "80x24+40+40"}, "xterm.log");
    auto shm = start({"weston-simple-shm"}, "shm.log");
    auto kde = desktop();
    const DesktopAbilities abilities = kde->abilities();
    EXPECT_TRUE(abilities.windows);
    EXPECT_TRUE(abilities.placement);
    ASSERT_EQ(kde->outputs().size(), 1u);
    EXPECT_EQ(kde->outputs()[0].rect, (WindowRect{0, 0, 1920, 1080}));
    EXPECT_FALSE(kde->outputs()[0].name.empty());

    std::optional<WindowInfo> x11;
    ASSERT_TRUE(wait_until([&] { return (x11 = kde->window_at(60, 60, {})) && x11->title == "umf-xterm"; }, 15s))
        << session->log();
    EXPECT_EQ(x11->wm_class, "xterm");  // KWin keeps WM_CLASS's class in lower case
    EXPECT_EQ(x11->instance, "xterm");
    EXPECT_EQ(x11->pid, xterm->pid());
    EXPECT_EQ(x11->output, kde->outputs()[0].name);

    // weston-simple-shm is 250x250, placed by KWin; find it through the list.
    std::optional<WindowInfo> native;
    ASSERT_TRUE(wait_until(
        [&] {
            for (int y = 0; y < 1080 && !native; y += 50)
                for (int x = 0; x < 1920 && !native; x += 50)
                    if (auto w = kde->window_at(x, y, {}); w && w->title == "simple-shm") native = w;
            return native.has_value();
        },
        15s));
    EXPECT_EQ(native->wm_class, "org.freedesktop.weston.simple-shm");
    EXPECT_EQ(native->instance, "");
    EXPECT_EQ(native->pid, shm->pid());

    // The provider's own windows are looked through.
    WindowFilter own;
    own.own_pids = {xterm->pid()};
    const auto through = kde->window_at(60, 60, own);
    EXPECT_TRUE(!through || through->pid != xterm->pid());

    // Aim-to-title latency: what a phone's aim costs.
    std::vector<double> ms;
    for (int i = 0; i < 30; ++i) {
        const auto t0 = Clock::now();
        const auto w = kde->window_at(60, 60, {});
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        ASSERT_TRUE(w && w->title == "umf-xterm");
    }
    std::sort(ms.begin(), ms.end());
    std::printf("KWin window_at latency over 30 queries: median %.1f ms, max %.1f ms\n", ms[15], ms.back());
    EXPECT_LT(ms[15], 500.0);
}

TEST_F(KdeDesktop, SnapshotsNeedKWinsScreenshotInterfaceAndSaySoWhenItIsMissing) {
    UMF_NEEDS_KWIN();
    auto kde = desktop();
    const DesktopAbilities abilities = kde->abilities();
    const bool has_interface =
        run({"gdbus", "call", "--session", "-d", "org.freedesktop.DBus", "-o", "/org/freedesktop/DBus", "-m",
             "org.freedesktop.DBus.NameHasOwner", "org.kde.KWin.ScreenShot2"},
            session->env())
            .find("true") != std::string::npos;
    if (has_interface) {
        // The test binary has no desktop file: KWin must refuse it, and say so.
        EXPECT_FALSE(abilities.snapshots);
        EXPECT_THROW(kde->capture({0, 0, 10, 10}), DesktopError);
        GTEST_SKIP() << "KWin has OpenGL compositing here; the authorised capture needs an installed desktop file";
    }
    EXPECT_FALSE(abilities.snapshots);
    std::string notes;
    for (const auto& note : abilities.notes) notes += note + "\n";
    EXPECT_NE(notes.find("org.kde.KWin.ScreenShot2"), std::string::npos) << notes;
    try {
        kde->capture({0, 0, 10, 10});
        ADD_FAILURE() << "a capture without the interface succeeded";
    } catch (const DesktopError& e) {
        EXPECT_NE(std::string(e.what()).find("OpenGL"), std::string::npos) << e.what();
    }
}

// KWin compositing with OpenGL (llvmpipe), as on a desktop with a GPU:
// its screenshot interface is there; it refuses a program no installed
// desktop file grants it to, and gives the pixels as shown once one does
// (here the test program itself, its entry written into the session's data
// folder while KWin runs, as `umf-provider kde install` does).
TEST_F(KdeDesktop, SnapshotsComeThroughKWinsScreenshotOnceADesktopFileGrantsThem) {
    if (const auto missing = kwin_missing()) GTEST_SKIP() << *missing;
    if (!find_program("xterm")) GTEST_SKIP() << "xterm is not installed (Debian: apt-get install -y xterm)";
    ensure_gui_application();
    session = std::make_unique<KWinSession>(start_kwin({.opengl = true}));
    EXPECT_NE(session->log().find("OpenGL renderer"), std::string::npos) << session->log();

    auto xterm = start({"xterm", "-title", "umf-blue", "-bg", "#336699", "-fg", "#336699", "-geometry", "60x20+80+60"},
                       "xterm.log");
    auto kde = desktop();
    std::optional<WindowInfo> window;
    ASSERT_TRUE(wait_until([&] { return (window = kde->window_at(150, 150, {})) && window->title == "umf-blue"; }, 15s))
        << session->log();
    // The middle of the window, away from its borders: its background as
    // shown (the text in the same colour, so nothing else is drawn there).
    const WindowRect& r = window->rect;
    const WindowRect middle{r.x + r.width / 4, r.y + r.height / 4, r.width / 2, r.height / 2};

    EXPECT_FALSE(kde->abilities().snapshots);
    try {
        kde->capture(middle);
        ADD_FAILURE() << "KWin gave a screenshot to a program no desktop file grants it to";
    } catch (const DesktopError& e) {
        EXPECT_NE(std::string(e.what()).find("umf-provider kde install"), std::string::npos) << e.what();
    }

    install_application(*session, "umf-tests", "/proc/self/exe", "org.kde.KWin.ScreenShot2");
    Capture capture;
    std::string refusal;
    // KWin reads the new entry within a few seconds.
    ASSERT_TRUE(wait_until(
        [&] {
            try {
                capture = kde->capture(middle);
            } catch (const DesktopError& e) {
                refusal = e.what();
                return false;
            }
            return !capture.pixels.empty() && capture.pixels[capture.pixels.size() / 2] == 0xff336699u;
        },
        30s))
        << "the window's colour did not come through: " << refusal;
    ASSERT_EQ(capture.width, middle.width);
    ASSERT_EQ(capture.height, middle.height);
    const auto blue = std::count(capture.pixels.begin(), capture.pixels.end(), 0xff336699u);
    EXPECT_EQ(blue, static_cast<long>(capture.pixels.size())) << "of " << capture.pixels.size() << " pixels";
    EXPECT_TRUE(desktop()->abilities().snapshots);
}

TEST_F(KdeDesktop, KWinOffersTheLayerShellTheFieldNeeds) {
    UMF_NEEDS_KWIN();
    const WaylandFacts facts =
        query_wayland((session->runtime / session->wayland_display).string(), std::chrono::milliseconds(2000));
    EXPECT_TRUE(facts.globals.count("zwlr_layer_shell_v1")) << "KWin 5.26+ offers wlr-layer-shell";
    auto kde = desktop();
    // No surface factory given: no field, and a note that says why.
    EXPECT_FALSE(kde->abilities().field);
    EXPECT_EQ(kde->make_field_surface(nullptr, {}, {}), nullptr);
}

TEST_F(KdeDesktop, APutsNewWindowIsMovedCentredOnThePlace) {
    UMF_NEEDS_KWIN();
    auto kde = desktop();
    const WindowPlacement where{1200.0, 500.0, {0, 0, 1920, 1080}};
    auto watch = kde->watch_new_window(where);
    ASSERT_TRUE(watch);
    auto xterm = start({"xterm", "-title", "umf-put", "-geometry", "40x10+0+0"}, "put.log");
    const auto moved = watch->place(xterm->pid(), std::chrono::milliseconds(5000));
    ASSERT_TRUE(moved) << session->log();
    const auto at = kde->window_at(1200, 500, {});
    ASSERT_TRUE(at);
    EXPECT_EQ(at->title, "umf-put");
    EXPECT_EQ(at->id, *moved);
    EXPECT_NEAR(at->rect.x + at->rect.width / 2.0, 1200.0, 1.0);
    EXPECT_NEAR(at->rect.y + at->rect.height / 2.0, 500.0, 1.0);
}

TEST_F(KdeDesktop, AStuckKWinGivesNoWindowAfterTheTimeoutAndAnswersAgainWhenItWakes) {
    UMF_NEEDS_KWIN();
    auto xterm = start({"xterm", "-title", "umf-xterm", "-geometry", "80x24+40+40"}, "xterm.log");
    auto kde = desktop();
    ASSERT_TRUE(wait_until([&] { auto w = kde->window_at(60, 60, {}); return w && w->title == "umf-xterm"; }, 15s));
    ::kill(session->kwin->pid(), SIGSTOP);
    const auto t0 = Clock::now();
    const auto stuck = kde->window_at(60, 60, {});
    const auto waited = Clock::now() - t0;
    ::kill(session->kwin->pid(), SIGCONT);
    EXPECT_FALSE(stuck);
    EXPECT_GE(waited, 900ms);  // the 1 s timeout, not an instant failure
    EXPECT_LT(waited, 3s);
    EXPECT_TRUE(wait_until([&] { auto w = kde->window_at(60, 60, {}); return w && w->title == "umf-xterm"; }, 10s));
}

TEST_F(KdeDesktop, AKWinThatIsGoneGivesNoWindowQuicklyInsteadOfAHang) {
    UMF_NEEDS_KWIN();
    auto kde = desktop();
    session->kwin->stop();
    const auto t0 = Clock::now();
    EXPECT_FALSE(kde->window_at(60, 60, {}));
    EXPECT_LT(Clock::now() - t0, 3s);
    EXPECT_THROW(kde->capture({0, 0, 10, 10}), DesktopError);
    EXPECT_TRUE(kde->outputs().empty());
    // And a KdeDesktop cannot be made without KWin.
    EXPECT_THROW(desktop(), DesktopError);
}

}  // namespace

#endif
