// The provider outlives its display: the keeper's rules on their own (which
// sockets mean a display is there, how a child's end reads, the shared items
// kept in a file, the keeper's turns with children it forks), and a real
// provider whose X server dies and comes back: it serves on at the same
// port with what was shared, and shows itself on the new server.
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "provider/commands/desktop_keeper.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/content/shared_items_file.hpp"
#include "provider/desktop/display_socket.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;
using namespace umf::test;

TEST(DisplaySocket, EachNamedDisplayHasItsSockets) {
    DesktopFacts facts;
    facts.wayland_display = "wayland-1";
    facts.x_display = ":3.0";
    const auto sockets = display_sockets(facts, "/run/user/1000");
    ASSERT_EQ(sockets.size(), 3u);
    EXPECT_EQ(sockets[0].path, fs::path("/run/user/1000/wayland-1"));
    EXPECT_EQ(sockets[1].path, fs::path("/tmp/.X11-unix/X3"));
    EXPECT_FALSE(sockets[1].abstract);
    EXPECT_TRUE(sockets[2].abstract);

    facts.wayland_display = "/tmp/elsewhere/wl";
    facts.x_display = "unix:12";
    const auto absolute = display_sockets(facts, "/run/user/1000");
    ASSERT_EQ(absolute.size(), 3u);
    EXPECT_EQ(absolute[0].path, fs::path("/tmp/elsewhere/wl"));
    EXPECT_EQ(absolute[1].path, fs::path("/tmp/.X11-unix/X12"));

    // Another host's display, or nonsense, names no local socket.
    facts = {};
    facts.x_display = "far.example:0";
    EXPECT_TRUE(display_sockets(facts, "").empty());
    facts.x_display = ":zero";
    EXPECT_TRUE(display_sockets(facts, "").empty());
}

TEST(DisplaySocket, ADisplayAnswersWhileItsServerListens) {
    TempDir dir;
    DesktopFacts facts;
    facts.wayland_display = "wayland-test";
    EXPECT_FALSE(displays_answer(facts, dir.path.string()));
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string path = (dir.path / "wayland-test").string();
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", path.c_str());
    ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(::listen(fd, 4), 0);
    EXPECT_TRUE(displays_answer(facts, dir.path.string()));
    ::close(fd);  // the file stays, as a dead compositor's does
    EXPECT_TRUE(fs::exists(path));
    EXPECT_FALSE(displays_answer(facts, dir.path.string()));
}

TEST(DesktopKeeper, AChildsEndSaysWhetherTheProviderIsDone) {
    EXPECT_TRUE(describe_child_end(0).done);            // exit 0
    EXPECT_TRUE(describe_child_end(3 << 8).done);       // exit 3: the configuration
    const ChildEnd qt = describe_child_end(1 << 8);     // Qt: "The X11 connection broke"
    EXPECT_FALSE(qt.done);
    EXPECT_EQ(qt.how, "exit 1");
    const ChildEnd killed = describe_child_end(SIGKILL);
    EXPECT_FALSE(killed.done);
    EXPECT_EQ(killed.how, "killed by SIGKILL");
}

TEST(SharedItemsFile, SharedItemsComeBackWithTheirIds) {
    TempDir dir;
    std::ofstream(dir.path / "notes.txt") << "notes";
    std::ofstream(dir.path / "gone.txt") << "soon gone";
    SharedItems before;
    const fs::path file = dir.path / "shared.json";
    before.on_change([&](const std::vector<SharedItem>& items) { save_shared_items(file, items); });
    SharedItem notes;
    notes.file = dir.path / "notes.txt";
    notes.rect = {10, 20, 300, 200};
    notes.screen = 1;
    SharedItem site;
    site.url = "https://example.org/a";
    site.title = "Example";
    site.rect = {0, 0, 50, 50};
    SharedItem gone;
    gone.file = dir.path / "gone.txt";
    gone.rect = {0, 0, 5, 5};
    const int first = before.add(notes);
    const int gone_id = before.add(gone);
    const int third = before.add(site);
    ASSERT_TRUE(before.remove(gone_id));
    EXPECT_EQ(load_shared_items(file).size(), 2u) << "a removal is written too";
    before.add(gone);
    fs::remove(dir.path / "gone.txt");

    SharedItems after;
    EXPECT_EQ(after.restore(load_shared_items(file)), 2) << "the item whose file went is left out";
    const auto items = after.items();
    ASSERT_EQ(items.size(), 2u);
    EXPECT_EQ(items[0].id, first);
    EXPECT_EQ(items[0].title, "notes.txt");
    EXPECT_EQ(items[0].screen, 1);
    EXPECT_EQ(items[0].rect, (PixelRect{10, 20, 300, 200}));
    EXPECT_EQ(items[1].id, third);
    EXPECT_EQ(items[1].url, std::optional<std::string>("https://example.org/a"));
    // New items take ids after the restored ones: `share --remove ID` stays unambiguous.
    SharedItem more = site;
    EXPECT_GT(after.add(more), third);

    EXPECT_TRUE(load_shared_items(dir.path / "none.json").empty());
    std::ofstream(dir.path / "bad.json") << "{\"not\": \"a list\"}";
    EXPECT_THROW(load_shared_items(dir.path / "bad.json"), std::runtime_error);
    EXPECT_EQ(fs::status(file).permissions() & (fs::perms::group_all | fs::perms::others_all), fs::perms::none);
}

// The keeper's turns, with children that play the parts: the desktop
// provider ends as Qt ends it (exit 1), the one without a desktop serves
// until stopped, the display answers, the desktop provider comes back and
// ends as a provider does (exit 0).
TEST(DesktopKeeper, ServesWithoutTheDesktopUntilTheDisplayAnswers) {
    TempDir dir;
    const fs::path turns = dir.path / "turns";
    std::ofstream(turns).close();
    const pid_t test = ::fork();
    ASSERT_GE(test, 0);
    if (test == 0) {
        // The keeper runs in a process of its own: it blocks signals and forks.
        sigset_t signals;
        sigemptyset(&signals);
        sigaddset(&signals, SIGINT);
        sigaddset(&signals, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &signals, nullptr);
        KeeperSettings settings;
        settings.shares_file = dir.path / "shared.json";
        settings.poll = std::chrono::milliseconds(50);
        settings.display_answers = [&] {
            std::ifstream in(turns);
            const std::string text{std::istreambuf_iterator<char>(in), {}};
            return text.find("without") != std::string::npos;  // once the fallback serves
        };
        std::ostringstream log;
        const auto role = keep_provider(settings, log);
        if (const int* code = std::get_if<int>(&role)) {
            std::ofstream(turns, std::ios::app) << "keeper " << *code << "\n" << log.str();
            ::_exit(*code == 0 ? 0 : 10);
        }
        const KeeperRole& r = std::get<KeeperRole>(role);
        std::ifstream in(turns);
        const std::string before{std::istreambuf_iterator<char>(in), {}};
        const bool second_desktop = before.find("desktop") != std::string::npos;
        std::ofstream(turns, std::ios::app) << (r.with_desktop ? "desktop\n" : "without\n");
        tell_keeper_port(r, 4321);
        if (r.with_desktop) ::_exit(second_desktop ? 0 : 1);
        int signal = 0;
        sigwait(&signals, &signal);
        ::_exit(0);
    }
    int status = 0;
    for (int i = 0; i < 200 && ::waitpid(test, &status, WNOHANG) == 0; ++i) ::usleep(50'000);
    if (::waitpid(test, &status, WNOHANG) == 0) {
        ::kill(test, SIGKILL);
        ::waitpid(test, &status, 0);
        FAIL() << "the keeper did not finish";
    }
    std::ifstream in(turns);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
    EXPECT_EQ(text.find("desktop\nwithout\ndesktop\nkeeper 0\n"), 0u) << text;
    EXPECT_NE(text.find("the provider on the desktop ended (exit 1)"), std::string::npos) << text;
    EXPECT_NE(text.find("the display answers again"), std::string::npos) << text;
}

std::string read_log(const fs::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The provider on a real X server that dies and comes back.
TEST(DesktopKeeper, TheProviderOutlivesItsXServer) {
    for (const char* program : {"Xvfb", "curl"})
        if (!find_program(program)) GTEST_SKIP() << program << " is not installed";
    TempDir dir;
    // A display number of its own, far above those other sessions' Xwayland
    // take while this one is down (it must be free again to come back on).
    int number = 90;
    while (number < 190 && (fs::exists("/tmp/.X" + std::to_string(number) + "-lock") ||
                            fs::exists("/tmp/.X11-unix/X" + std::to_string(number))))
        ++number;
    const std::string display = ":" + std::to_string(number);
    const auto start_x = [&](const std::string& log) {
        Process::Options x;
        x.log = dir.path / log;
        auto process = std::make_unique<Process>(
            std::vector<std::string>{"Xvfb", display, "-screen", "0", "1280x720x24", "-nolisten", "tcp", "-noreset"}, x);
        if (!wait_until([&] { return fs::exists("/tmp/.X11-unix/X" + std::to_string(number)); }, 10s))
            ADD_FAILURE() << "Xvfb did not start on " << display << ": " << read_log(dir.path / log);
        return process;
    };
    XServer server{start_x("xvfb.log"), display};
    const fs::path runtime = dir.path / "run";
    fs::create_directory(runtime);
    fs::permissions(runtime, fs::perms::owner_all);
    Process::Options options;
    options.cwd = dir.path;
    options.env = environment_with({{"DISPLAY", server.display},
                                    {"QT_QPA_PLATFORM", "xcb"},
                                    {"WAYLAND_DISPLAY", ""},
                                    {"XDG_SESSION_TYPE", "x11"},
                                    {"XDG_RUNTIME_DIR", runtime.string()}});
    options.log = dir.path / "provider.log";
    Process provider({UMF_PROVIDER_TOOL, "--bind", "127.0.0.1", "--port", "0", "--no-qr", "--puts", "never", "--config-dir",
                      (dir.path / "cfg").string()},
                     options);
    const fs::path log = dir.path / "provider.log";
    ASSERT_TRUE(wait_until([&] { return count(read_log(log), "desktop: x11") == 1; }, 20s)) << read_log(log);
    const std::string first = read_log(log);
    const auto at = first.find("listening on https://127.0.0.1:");
    ASSERT_NE(at, std::string::npos) << first;
    const std::string port = first.substr(at + 31, first.find(' ', at + 31) - at - 31);
    const auto control = [&](const std::string& args) {
        return run_command("XDG_RUNTIME_DIR=" + runtime.string() + " " + UMF_PROVIDER_TOOL + " " + args + " --port " +
                           port + " 2>&1");
    };
    const auto page_status = [&] {
        return run_command("curl -s -k --max-time 10 -o /dev/null -w '%{http_code}' https://127.0.0.1:" + port + "/").out;
    };
    std::ofstream(dir.path / "notes.txt") << "notes";
    ASSERT_EQ(control("share " + (dir.path / "notes.txt").string() + " --rect 0,0,200,100").exit_code, 0);
    EXPECT_EQ(page_status(), "200");

    // The X server dies: Qt ends the desktop provider, the keeper serves on.
    server.process.reset();
    ASSERT_TRUE(wait_until([&] { return read_log(log).find("Serving on without a desktop") != std::string::npos; }, 10s))
        << read_log(log);
    ASSERT_TRUE(wait_until([&] { return count(read_log(log), "listening on https://127.0.0.1:" + port) == 2; }, 20s))
        << read_log(log);
    EXPECT_EQ(page_status(), "200") << read_log(log);
    auto listed = control("share --list");
    EXPECT_NE(listed.out.find("notes.txt"), std::string::npos) << listed.out << read_log(log);

    // It comes back, on the same display: so does the desktop provider.
    auto again = start_x("xvfb-again.log");
    ASSERT_TRUE(wait_until([&] { return count(read_log(log), "desktop: x11") == 2; }, 30s))
        << read_log(log) << "\nXvfb: " << read_log(dir.path / "xvfb-again.log");
    EXPECT_NE(read_log(log).find("the display answers again"), std::string::npos);
    EXPECT_EQ(page_status(), "200") << read_log(log);
    listed = control("share --list");
    EXPECT_NE(listed.out.find("notes.txt"), std::string::npos) << listed.out << read_log(log);

    ::kill(provider.pid(), SIGTERM);
    const auto status = provider.wait_exit(15s);
    ASSERT_TRUE(status.has_value()) << read_log(log);
    EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << read_log(log);
    const std::string end = "umf-provider: stopped\n";
    const std::string all = read_log(log);
    EXPECT_EQ(all.rfind(end), all.size() - end.size()) << all;
    // Nothing left behind: the shared items' file goes with the keeper.
    for (const auto& entry : fs::directory_iterator(runtime / "umf"))
        EXPECT_EQ(entry.path().extension(), ".sock") << entry.path();
}

}  // namespace

#endif
