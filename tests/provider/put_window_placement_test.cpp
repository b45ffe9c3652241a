// Where an accepted put opens (provider/desktop/window_placement.hpp): the
// window's place centred on the pointed position and kept on its screen,
// which new window is chosen, the process ancestry that prefers the opener's
// own; and for real, on Xvfb with openbox, a fake xdg-open that starts an
// xterm whose window lands centred on the pointed place, while no new window
// or no window manager moves nothing. The X11 part is skipped when Xvfb,
// openbox or xterm are missing (Debian: xvfb openbox xterm).
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <future>

#include "provider/desktop/x11/x11_desktop.hpp"
#include "provider/desktop/x11/x11_window_watch.hpp"
#include "provider/put/desktop_open.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using namespace umf::test;
using namespace std::chrono_literals;

TEST(PutWindowPlacement, CentredOnThePointAndKeptOnItsScreen) {
    const PlaceRect screen{1920, 0, 1600, 1000};  // the second of two screens
    const PlaceRect middle = centred_on(400, 300, 2720, 500, screen);
    EXPECT_EQ(middle.x, 2520);
    EXPECT_EQ(middle.y, 350);
    EXPECT_EQ(middle.width, 400);
    EXPECT_EQ(middle.height, 300);
    // Near the bottom-right corner: moved in just enough.
    const PlaceRect corner = centred_on(400, 300, 3515, 995, screen);
    EXPECT_EQ(corner.x, 1920 + 1600 - 400);
    EXPECT_EQ(corner.y, 1000 - 300);
    // Near the left edge, which is another screen's right edge: not onto it.
    EXPECT_EQ(centred_on(400, 300, 1925, 500, screen).x, 1920);
    // Larger than the screen: its top-left corner stays on it.
    const PlaceRect big = centred_on(2000, 1200, 2720, 500, screen);
    EXPECT_EQ(big.x, 1920);
    EXPECT_EQ(big.y, 0);
}

TEST(PutWindowPlacement, TheOpenersWindowFirstThenTheFirstNewNormalOne) {
    const std::vector<unsigned long> before{10, 11};
    const auto none = [](unsigned long) { return false; };
    const auto all = [](unsigned long) { return true; };
    // 12 is new and normal, 13 new and the opener's: 13.
    EXPECT_EQ(pick_new_window(before, {10, 11, 12, 13}, [](unsigned long w) { return w == 13; }, all), 13ul);
    // Nobody's from the opener: the first new normal one.
    EXPECT_EQ(pick_new_window(before, {12, 10, 13, 11}, none, [](unsigned long w) { return w == 13; }), 13ul);
    EXPECT_EQ(pick_new_window(before, {10, 11, 12, 13}, none, all), 12ul);
    // Windows that were there already never move, even the opener's.
    EXPECT_EQ(pick_new_window(before, {11, 10}, all, all), std::nullopt);
    // New, but a dock or a splash: no.
    EXPECT_EQ(pick_new_window(before, {10, 11, 12}, none, none), std::nullopt);
    EXPECT_EQ(pick_new_window({}, {}, all, all), std::nullopt);
}

TEST(PutWindowPlacement, AncestryFollowsTheParentChain) {
    EXPECT_TRUE(descends_from(::getpid(), ::getpid()));
    EXPECT_TRUE(descends_from(::getpid(), ::getppid()));
    EXPECT_FALSE(descends_from(::getppid(), ::getpid()));
    EXPECT_FALSE(descends_from(::getpid(), 1)) << "everything descends from init: it names no opener";
    TempDir dir;
    // A grandchild: sh starts sleep in the background and waits for it.
    Process::Options options;
    options.log = dir.path / "sh.log";
    Process sh({"/bin/sh", "-c", "sleep 30 & echo $! > '" + (dir.path / "pid").string() + "'; wait"}, options);
    ASSERT_TRUE(wait_until([&] { return fs::exists(dir.path / "pid") && fs::file_size(dir.path / "pid") > 0; }, 5s));
    int grandchild = 0;
    std::ifstream(dir.path / "pid") >> grandchild;
    ASSERT_GT(grandchild, 0);
    EXPECT_TRUE(descends_from(grandchild, sh.pid()));
    EXPECT_TRUE(descends_from(grandchild, ::getpid()));
    EXPECT_FALSE(descends_from(sh.pid(), grandchild));
    EXPECT_FALSE(descends_from(999999999, ::getpid())) << "no such process";
}

// $NAME set while it lives, restored after (open_with_desktop reads DISPLAY
// and PATH from the process's environment, as `serve` has them).
class ScopedEnv {
public:
    ScopedEnv(std::string name, const std::string& value) : name_(std::move(name)) {
        if (const char* old = ::getenv(name_.c_str())) old_ = old;
        ::setenv(name_.c_str(), value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_.c_str(), old_->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }

private:
    std::string name_;
    std::optional<std::string> old_;
};

// The real X11 watch, telling the test when its thread is done with the X
// server (which the test must outlive: Xlib ends the process when the
// server goes while a connection is open).
class WatchDone final : public NewWindowWatch {
public:
    explicit WatchDone(std::unique_ptr<NewWindowWatch> inner) : inner_(std::move(inner)) {}
    std::optional<unsigned long> place(int child_pid, std::chrono::milliseconds wait) override {
        auto placed = inner_->place(child_pid, wait);
        inner_.reset();
        done_.set_value();
        return placed;
    }
    std::shared_future<void> done() const { return future_; }

private:
    std::unique_ptr<NewWindowWatch> inner_;
    std::promise<void> done_;
    std::shared_future<void> future_ = done_.get_future().share();
};

// Xvfb of 1600x1000 with openbox managing it.
class PutWindowPlacementOnX : public ::testing::Test {
protected:
    TempDir dir;
    XServer server;
    std::unique_ptr<Process> openbox;
    std::unique_ptr<X11Desktop> desktop;

    void SetUp() override {
        for (const char* program : {"Xvfb", "openbox", "xterm"})
            if (!find_program(program))
                GTEST_SKIP() << program << " is not installed (Debian: apt-get install xvfb openbox xterm)";
        server = start_xvfb(dir.path / "xvfb.log", "1600x1000x24");
        desktop = std::make_unique<X11Desktop>(server.display);
    }
    void TearDown() override {
        desktop.reset();  // before the server goes, or Xlib exits the process
        openbox.reset();
        server.process.reset();
    }
    Process::Options options(const std::string& log) const {
        Process::Options o;
        o.env = environment_with({{"DISPLAY", server.display}, {"HOME", dir.path.string()}});
        o.log = dir.path / log;
        return o;
    }
    void start_openbox() {
        openbox = umf::test::start_openbox(options("openbox.log"), dir.path / "openbox-ready");
        ASSERT_TRUE(desktop->has_ewmh());
    }
    std::optional<WindowInfo> window_titled(const std::string& title) const {
        for (const WindowInfo& w : desktop->windows())
            if (w.title == title) return w;
        return std::nullopt;
    }
};

TEST_F(PutWindowPlacementOnX, XdgOpensWindowLandsCentredOnThePointedPlace) {
    start_openbox();
    // An xdg-open that opens "the URL" as an xterm titled after it, and says
    // which process it became, so the test can end it.
    const fs::path bin = dir.path / "bin";
    fs::create_directories(bin);
    const fs::path pids = dir.path / "opened-pids";
    std::ofstream(bin / "xdg-open") << "#!/bin/sh\necho $$ >> '" << pids.string()
                                    << "'\nexec xterm -geometry 50x12 -T \"$1\" -e sleep 60\n";
    ::chmod((bin / "xdg-open").c_str(), 0755);
    ScopedEnv display("DISPLAY", server.display);
    ScopedEnv path("PATH", bin.string() + ":" + (::getenv("PATH") ? ::getenv("PATH") : "/usr/bin:/bin"));
    const PlaceRect screen{0, 0, 1600, 1000};

    std::string problem;
    std::vector<std::shared_future<void>> watching;
    const auto watch = [&](WindowPlacement where) {
        auto watch = std::make_unique<WatchDone>(X11NewWindowWatch::create(where));
        watching.push_back(watch->done());
        return watch;
    };
    ASSERT_TRUE(open_with_desktop("placed-middle", &problem, watch({1100, 400, screen}))) << problem;
    // Near a corner: kept on the screen, moved in no further than needed.
    ASSERT_TRUE(open_with_desktop("placed-corner", &problem, watch({1595, 995, screen}))) << problem;
    // Without a place: where the window manager puts it.
    ASSERT_TRUE(open_with_desktop("placed-nowhere", &problem)) << problem;

    std::optional<WindowInfo> middle, corner;
    const bool placed = wait_until(
        [&] {
            middle = window_titled("placed-middle");
            corner = window_titled("placed-corner");
            return middle && corner && std::abs(middle->rect.x + middle->rect.width / 2 - 1100) <= 1 &&
                   corner->rect.x + corner->rect.width == 1600;
        },
        10s);
    EXPECT_TRUE(placed) << "middle " << (middle ? std::to_string(middle->rect.x) : "none") << ", corner "
                        << (corner ? std::to_string(corner->rect.x) : "none");
    ASSERT_TRUE(middle && corner);
    EXPECT_LE(std::abs(middle->rect.x + middle->rect.width / 2 - 1100), 1);
    EXPECT_LE(std::abs(middle->rect.y + middle->rect.height / 2 - 400), 1);
    EXPECT_EQ(corner->rect.x + corner->rect.width, 1600);
    EXPECT_EQ(corner->rect.y + corner->rect.height, 1000);
    ASSERT_TRUE(wait_until([&] { return window_titled("placed-nowhere").has_value(); }, 10s));
    const WindowInfo nowhere = *window_titled("placed-nowhere");
    // Left where openbox put it: neither of the places the others went to.
    EXPECT_FALSE(std::abs(nowhere.rect.x + nowhere.rect.width / 2 - 1100) <= 1 &&
                 std::abs(nowhere.rect.y + nowhere.rect.height / 2 - 400) <= 1);
    EXPECT_FALSE(nowhere.rect.x + nowhere.rect.width == 1600 && nowhere.rect.y + nowhere.rect.height == 1000);

    for (const auto& done : watching) EXPECT_EQ(done.wait_for(20s), std::future_status::ready);
    std::ifstream in(pids);
    for (int pid = 0; in >> pid;)
        if (pid > 1) ::kill(pid, SIGTERM);
}

TEST_F(PutWindowPlacementOnX, OnlyANewWindowMovesAndWithoutAWindowManagerNothingIsWatched) {
    EXPECT_EQ(X11NewWindowWatch::create({800, 500, {0, 0, 1600, 1000}}, server.display), nullptr)
        << "no window manager lists the windows";
    start_openbox();
    Process old({"xterm", "-T", "old", "-e", "sleep", "60"}, options("old.log"));
    ASSERT_TRUE(wait_until([&] { return window_titled("old").has_value(); }, 10s));
    const WindowRect before = window_titled("old")->rect;
    auto watch = X11NewWindowWatch::create({800, 500, {0, 0, 1600, 1000}}, server.display);
    ASSERT_NE(watch, nullptr);
    // The "opener" brings up no window of its own: the old one stays put.
    Process quiet({"sleep", "30"}, options("sleep.log"));
    EXPECT_EQ(watch->place(quiet.pid(), 600ms), std::nullopt);
    EXPECT_EQ(window_titled("old")->rect, before);
    // A window that comes while it watches is the one moved.
    auto second = X11NewWindowWatch::create({800, 500, {0, 0, 1600, 1000}}, server.display);
    ASSERT_NE(second, nullptr);
    Process fresh({"xterm", "-T", "fresh", "-e", "sleep", "60"}, options("fresh.log"));
    const auto moved = second->place(fresh.pid(), 10s);
    ASSERT_TRUE(moved);
    ASSERT_TRUE(wait_until(
        [&] {
            const auto w = window_titled("fresh");
            return w && w->id == *moved && std::abs(w->rect.x + w->rect.width / 2 - 800) <= 1 &&
                   std::abs(w->rect.y + w->rect.height / 2 - 500) <= 1;
        },
        5s));
    EXPECT_EQ(window_titled("old")->rect, before);
}

}  // namespace

#endif
