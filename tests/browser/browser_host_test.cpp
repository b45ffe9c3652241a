// umf-browser-host as a browser runs it: started with its standard input and
// output as the native-messaging port, it finds the provider's browser link
// (a real BrowserLink on a real Unix socket here) and relays both ways.
#ifdef UMF_PROVIDER_TESTS
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>

#include <atomic>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <thread>

#include "browser/host/native_messaging.hpp"
#include "provider/browser/browser_link.hpp"
#include "provider/browser/browser_resolver.hpp"
#include "provider/common/owner_socket.hpp"
#include "provider/desktop/x11/x11_desktop.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/x11_session.hpp"

namespace umf::provider {
namespace {

using json = nlohmann::json;
using namespace umf::test;
namespace fs = std::filesystem;

class BrowserHost : public ::testing::Test {
protected:
    TempDir dir;
    fs::path runtime;
    int to_host = -1, from_host = -1;
    std::unique_ptr<Process> host;
    browser::FrameReader reader{browser::kMaxToBrowser};

    void SetUp() override {
        runtime = dir.path / "run";
        fs::create_directories(runtime / "umf");
        ::chmod(runtime.c_str(), 0700);
        ::chmod((runtime / "umf").c_str(), 0700);
    }
    void TearDown() override {
        if (to_host >= 0) ::close(to_host);
        if (from_host >= 0) ::close(from_host);
    }

    void start_host() {
        int in[2], out[2];
        ASSERT_EQ(::pipe2(in, O_CLOEXEC), 0);
        ASSERT_EQ(::pipe2(out, O_CLOEXEC), 0);
        Process::Options o;
        o.env = environment_with({{"XDG_RUNTIME_DIR", runtime.string()}});
        o.log = dir.path / "host.log";
        o.stdin_fd = in[0];
        o.stdout_fd = out[1];
        host = std::make_unique<Process>(std::vector<std::string>{UMF_BROWSER_HOST_TOOL, "chrome-extension://x/"}, o);
        ::close(in[0]);
        ::close(out[1]);
        to_host = in[1];
        from_host = out[0];
    }

    void send(const json& message) {
        const std::string framed = browser::frame_message(message.dump(), browser::kMaxFromBrowser);
        ASSERT_EQ(::write(to_host, framed.data(), framed.size()), static_cast<ssize_t>(framed.size()));
    }

    // The next message from the host of the given type, within 10 s.
    std::optional<json> receive(const std::string& type) {
        const auto deadline = Clock::now() + 10s;
        for (;;) {
            while (auto text = reader.next()) {
                json m = json::parse(*text);
                if (m.value("type", "") == type) return m;
            }
            const std::string bytes = read_until(from_host, std::min(deadline, Clock::now() + 200ms), '\0');
            if (!bytes.empty()) reader.feed(bytes.data(), bytes.size());
            if (Clock::now() > deadline) return std::nullopt;
        }
    }

    std::string log() const { return read_text(dir.path / "host.log"); }
};

TEST_F(BrowserHost, RelaysWindowsAndQuestionsAndGivesTheBrowsersPid) {
    BrowserLink link;
    link.listen(runtime / "umf" / "browser-47999.sock");
    start_host();
    send({{"type", "hello"}, {"browser", "chromium"}, {"version", "156.0"}});
    send({{"type", "windows"},
          {"windows",
           {{{"id", 1}, {"left", 10}, {"top", 20}, {"width", 800}, {"height", 600}, {"focused", true},
             {"tab", {{"id", 5}, {"url", "https://example.org/"}, {"title", "Example"}}}},
            {{"id", 2}, {"incognito", true}, {"tab", {{"id", 6}, {"url", "https://secret.example/"}, {"title", "S"}}}}}}});
    ASSERT_TRUE(wait_until([&] { return !link.browsers().empty() && !link.browsers()[0].windows.empty(); }, 10s)) << log();
    const BrowserState b = link.browsers()[0];
    EXPECT_EQ(b.name, "chromium");
    EXPECT_EQ(b.pid, ::getpid()) << "the host's parent: the browser that started it";
    ASSERT_EQ(b.windows.size(), 1u) << "the private window is never kept";
    EXPECT_EQ(b.windows[0].tab.url, "https://example.org/");
    const auto status = receive("status");
    ASSERT_TRUE(status);
    EXPECT_EQ((*status)["provider"], true);

    // A question goes to the extension and its answer comes back.
    std::optional<json> answer;
    std::thread asker([&] {
        answer = link.ask(b.connection, {{"type", "element_at"}, {"window", 1}, {"tab", 5}, {"screen_x", 100}, {"screen_y", 200}},
                          5s);
    });
    const auto question = receive("element_at");
    ASSERT_TRUE(question);
    EXPECT_EQ((*question)["screen_x"], 100);
    send({{"type", "answer"}, {"req", (*question)["req"]}, {"element", {{"kind", "link"}, {"url", "https://example.org/x"}}}});
    asker.join();
    ASSERT_TRUE(answer);
    EXPECT_EQ((*answer)["element"]["url"], "https://example.org/x");

    // A question nobody answers, and one to a browser that is gone, end.
    const auto t0 = Clock::now();
    EXPECT_FALSE(link.ask(b.connection, {{"type", "element_at"}}, 300ms));
    EXPECT_LT(Clock::now() - t0, 3s);
    ::close(to_host);
    to_host = -1;
    ASSERT_TRUE(host->wait_exit(10s)) << "the host ends with its browser";
    ASSERT_TRUE(wait_until([&] { return link.browsers().empty(); }, 10s));
    EXPECT_FALSE(link.ask(b.connection, {{"type", "element_at"}}, 5s));
}

TEST_F(BrowserHost, WaitsForAProviderAndTellsItWhatItMissed) {
    start_host();
    send({{"type", "hello"}, {"browser", "firefox"}, {"version", "153.0"}});
    send({{"type", "windows"}, {"windows", {{{"id", 3}, {"tab", {{"id", 9}, {"url", "https://a.org/"}, {"title", "A"}}}}}}});
    send({{"type", "windows"}, {"windows", {{{"id", 4}, {"tab", {{"id", 9}, {"url", "https://b.org/"}, {"title", "B"}}}}}}});
    ASSERT_TRUE(wait_until([&] { return log().find("no provider is running") != std::string::npos; }, 10s)) << log();
    BrowserLink link;
    link.listen(runtime / "umf" / "browser-47998.sock");
    ASSERT_TRUE(wait_until([&] { return !link.browsers().empty() && !link.browsers()[0].windows.empty(); }, 15s)) << log();
    EXPECT_EQ(link.browsers()[0].name, "firefox");
    EXPECT_EQ(link.browsers()[0].windows[0].tab.url, "https://b.org/") << "the last report, not the first";
}

TEST_F(BrowserHost, OversizedAndMalformedMessagesEndOrPassHarmlessly) {
    BrowserLink link;
    link.listen(runtime / "umf" / "browser-47997.sock");
    start_host();
    // Not JSON, no type, a type the provider does not know: the host and the
    // link go on.
    for (const std::string text : {"{not json", "[1,2]", "{\"type\":\"launch_missiles\"}"}) {
        const std::string framed = browser::frame_message(text, browser::kMaxFromBrowser);
        ASSERT_EQ(::write(to_host, framed.data(), framed.size()), static_cast<ssize_t>(framed.size()));
    }
    const auto complaint = receive("error");
    ASSERT_TRUE(complaint) << log();
    EXPECT_NE((*complaint)["message"].get<std::string>().find("unknown message type"), std::string::npos);
    send({{"type", "hello"}, {"browser", "chromium"}});
    ASSERT_TRUE(wait_until([&] { return !link.browsers().empty(); }, 10s)) << log();
    // A frame announcing more than the host takes ends it (and its link).
    const std::uint32_t huge = 512u * 1024 * 1024;
    char header[4];
    std::memcpy(header, &huge, 4);
    ASSERT_EQ(::write(to_host, header, 4), 4);
    const auto status = host->wait_exit(10s);
    ASSERT_TRUE(status);
    EXPECT_NE(*status, 0);
    EXPECT_NE(log().find("more than"), std::string::npos) << log();
    EXPECT_TRUE(wait_until([&] { return link.browsers().empty(); }, 10s));
}

TEST_F(BrowserHost, TakesNoSocketFromAFolderOthersMayEnter) {
    ::chmod((runtime / "umf").c_str(), 0755);
    BrowserLink link;
    EXPECT_NO_THROW(link.listen(runtime / "umf" / "browser-47996.sock"));  // the link makes it 0700 again
    ::chmod((runtime / "umf").c_str(), 0755);
    start_host();
    send({{"type", "hello"}, {"browser", "chromium"}});
    std::this_thread::sleep_for(1s);
    EXPECT_TRUE(link.browsers().empty()) << "the host connected through a folder others may enter";
    ::chmod((runtime / "umf").c_str(), 0700);
    EXPECT_TRUE(wait_until([&] { return !link.browsers().empty(); }, 10s)) << log();
}

// A browser on the link, played by the test: it speaks the host's protocol
// for an xterm titled as a browser's window would be, on a throwaway X
// server, and answers the provider's questions with `answer` (nullopt: it
// stays silent).
class FakeBrowser {
    XServer server_;  // first made, last gone: the desktop's connection needs it

public:
    using Answer = std::function<std::optional<json>(const json& question)>;

    FakeBrowser(const TempDir& dir, const fs::path& socket, const json& windows, Answer answer)
        : server_(start_xvfb(dir.path / "xvfb.log", "800x600x24")) {
        const auto env = environment_with({{"DISPLAY", server_.display}});
        desktop = std::make_shared<const X11Desktop>(server_.display);
        xterm_ = std::make_unique<Process>(
            std::vector<std::string>{"xterm", "-T", "Fake page - Chromium", "-geometry", "80x24+10+10", "-e", "sleep",
                                     "60"},
            logged_in(dir.path, env, "xterm.log"));
        if (!wait_until([&] { return (window = desktop->window_at(100, 100, {})).has_value() && window->pid > 0; }, 20s))
            throw std::runtime_error("the xterm showed no window");
        link = std::make_shared<BrowserLink>();
        link->listen(socket);
        fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        const sockaddr_un addr = unix_address(link->path());
        if (::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
            throw std::runtime_error("cannot connect to the link");
        json report = windows;
        if (report.is_null()) report = json::array({window_report(window->rect)});
        write_line({{"type", "hello"}, {"browser", "chromium"}, {"pid", window->pid}});
        write_line({{"type", "windows"}, {"windows", report}});
        if (!wait_until([&] { return !link->browsers().empty() && !link->browsers()[0].windows.empty(); }, 10s))
            throw std::runtime_error("the link never listed the window");
        reader_ = std::thread([this, answer = std::move(answer)] {
            std::string got;
            char c;
            while (::read(fd_, &c, 1) == 1) {
                if (c != '\n') {
                    got += c;
                    continue;
                }
                const json q = json::parse(got);
                got.clear();
                ++asked;
                if (auto a = answer(q)) {
                    (*a)["type"] = "answer";
                    (*a)["req"] = q["req"];
                    write_line(*a);
                }
            }
        });
    }
    ~FakeBrowser() {
        ::shutdown(fd_, SHUT_RDWR);
        if (reader_.joinable()) reader_.join();
        ::close(fd_);
    }

    // The page's window as the extension reports it: the xterm's bounds.
    static json window_report(const WindowRect& r) {
        return {{"id", 1},
                {"left", r.x},
                {"top", r.y},
                {"width", r.width},
                {"height", r.height},
                {"tab", {{"id", 2}, {"url", "https://example.org/page"}, {"title", "Fake page"}}}};
    }

    std::shared_ptr<const X11Desktop> desktop;
    std::optional<WindowInfo> window;
    std::shared_ptr<BrowserLink> link;
    std::atomic<int> asked{0};

private:
    void write_line(const json& message) {
        const std::string line = message.dump() + "\n";
        [[maybe_unused]] auto n = ::write(fd_, line.data(), line.size());
    }

    std::unique_ptr<Process> xterm_;
    int fd_ = -1;
    std::thread reader_;
};

bool lacks_fake_browser_programs(std::string* missing) {
    for (const char* program : {"Xvfb", "xterm"})
        if (!find_program(program)) return *missing = program, true;
    return false;
}

// A browser that reports no bounds (as on Wayland) cannot place the point in
// its page: the page is given, and the page is not even asked.
TEST_F(BrowserHost, AWindowWithoutBoundsGivesItsPageNotAGuess) {
    std::string missing;
    if (lacks_fake_browser_programs(&missing)) GTEST_SKIP() << missing << " is not installed";
    const json unbounded = json::array(
        {{{"id", 1}, {"tab", {{"id", 2}, {"url", "https://example.org/page"}, {"title", "Fake page"}}}}});
    // Were the page asked, it would answer with a link.
    FakeBrowser browser(dir, runtime / "umf" / "browser-47995.sock", unbounded, [](const json&) -> std::optional<json> {
        return json{{"element", {{"kind", "link"}, {"url", "https://example.org/wrong"}}}};
    });
    const BrowserResolver resolver(browser.desktop, {}, browser.link);
    const auto resolved = resolver.resolve(ScreenPoint{0, 100, 100, 100, 100}, Purpose::grab);
    ASSERT_TRUE(resolved);
    EXPECT_EQ(resolved->url, "https://example.org/page");
    EXPECT_EQ(resolved->title, "Page: Fake page");
    EXPECT_EQ(browser.asked.load(), 0) << resolved->url << " " << resolved->title;
}

// A busy page that answers an aim too late: inside the link it last named,
// the aim keeps the link (the phone's title does not flick to the page);
// outside it, or for a grab, the page is what is known.
TEST_F(BrowserHost, ALateAnswerKeepsTheLinkStillUnderTheAim) {
    std::string missing;
    if (lacks_fake_browser_programs(&missing)) GTEST_SKIP() << missing << " is not installed";
    // Only the first question is answered: a link covering x 80..200, y 90..130.
    auto questions = std::make_shared<std::atomic<int>>(0);
    FakeBrowser browser(dir, runtime / "umf" / "browser-47994.sock", nullptr,
                        [questions](const json& q) -> std::optional<json> {
        if ((*questions)++ > 0 || q.value("type", "") != "element_at") return std::nullopt;
        return json{{"element",
                     {{"kind", "link"},
                      {"url", "https://example.org/notes"},
                      {"text", "Release notes"},
                      {"screen_rect", {80, 90, 120, 40}}}}};
    });
    BrowserResolverOptions options;
    options.aim_timeout = 500ms;  // long enough for the first answer on a loaded machine
    options.grab_timeout = 500ms;
    const BrowserResolver resolver(browser.desktop, {}, browser.link, nullptr, options);
    const auto at = [](double x, double y) { return ScreenPoint{0, x, y, x, y}; };
    const auto first = resolver.resolve(at(100, 100), Purpose::preview);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->url, "https://example.org/notes");
    const auto late = resolver.resolve(at(150, 120), Purpose::preview);
    ASSERT_TRUE(late);
    EXPECT_EQ(late->url, "https://example.org/notes") << late->title;
    const auto outside = resolver.resolve(at(100, 200), Purpose::preview);
    ASSERT_TRUE(outside);
    EXPECT_EQ(outside->title, "Page: Fake page");
    const auto grab = resolver.resolve(at(100, 100), Purpose::grab);
    ASSERT_TRUE(grab);
    EXPECT_EQ(grab->title, "Page: Fake page") << "a grab takes only what the page says now";
    EXPECT_EQ(browser.asked.load(), 4);
}

}  // namespace
}  // namespace umf::provider
#endif
