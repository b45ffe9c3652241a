// What the provider answers about content, without sockets: field points to
// screen points, the resolvers in order, content messages with one-time
// download links, the rate limits, public mode, and the download table.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "provider/content/board_resolver.hpp"
#include "provider/content/download_table.hpp"
#include "provider/content/file_facts.hpp"
#include "provider/content/shared_items.hpp"
#include "provider/service/control_socket.hpp"
#include "provider/service/pairing_qr.hpp"
#include "provider/service/service.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using umf::test::TempDir;

namespace fs = std::filesystem;
namespace p = umf::protocol;
using namespace umf::provider;
using namespace std::chrono_literals;

constexpr const char* kContentToken = "content-test-token-0123456789";

std::string grab_text(const std::string& id, double u, double v) {
    return p::encode(p::Grab{p::RequestId{id}, {u, v}});
}
std::string aim_text(int id, double u, double v) {
    return p::encode(p::Aim{p::RequestId{std::int64_t{id}}, {u, v}, 0.9});
}

class ProviderContent : public ::testing::Test {
protected:
    TempDir dir;
    fs::path report;
    std::shared_ptr<SharedItems> shared = std::make_shared<SharedItems>();
    std::unique_ptr<Service> service;
    SessionState state;
    SteadyTime now = std::chrono::steady_clock::now();

    void SetUp() override {
        report = dir.path / "report.pdf";
        std::ofstream(report) << "%PDF-1.4 not really";
        Board board;
        board.items.push_back({"Report", report, std::nullopt, std::nullopt, std::nullopt});
        board.items.push_back({"Site", std::nullopt, "https://example.org/", std::nullopt, std::nullopt});
        // Left half of a 1920 x 1080 screen: the report; the right half's top: the site.
        std::vector<PixelRect> tiles = {{0, 0, 960, 1080}, {960, 0, 960, 540}};
        make_service(std::make_shared<BoardResolver>(board, tiles), false);
    }
    void make_service(std::shared_ptr<const Resolver> board, bool public_mode) {
        ServiceConfig config = default_service_config(1920, 1080);
        config.public_mode = public_mode;
        std::vector<std::shared_ptr<const Resolver>> resolvers{std::move(board)};
        if (!public_mode) resolvers.push_back(shared);
        service = std::make_unique<Service>(config, kContentToken, resolvers);
        state = SessionState{};
        state.peer = "192.0.2.1";
        auto out = service->handle_text(state, p::encode(p::Hello{std::nullopt, kContentToken, "test"}), now);
        ASSERT_TRUE(state.welcomed);
    }
    p::Message one(const std::string& text) {
        auto out = service->handle_text(state, text, now);
        EXPECT_EQ(out.replies.size(), 1u) << text;
        return out.replies.empty() ? p::Message{p::Error{}} : out.replies[0];
    }
};

TEST_F(ProviderContent, FieldPointsMapToScreenPixels) {
    // b4-64x36 covers 1920 x 1080 exactly at 30 px a module.
    const auto a = service->screen_point({10.0, 20.0});
    ASSERT_TRUE(a);
    EXPECT_DOUBLE_EQ(a->x, 300.0);
    EXPECT_DOUBLE_EQ(a->y, 600.0);
    EXPECT_FALSE(service->screen_point({64.0, 1.0}));
    EXPECT_FALSE(service->screen_point({-0.01, 1.0}));
    EXPECT_FALSE(service->screen_point({1.0, 36.5}));
}

TEST_F(ProviderContent, AimsPreviewAndGrabsTakeWithDownloadLinks) {
    const auto target = std::get<p::Target>(one(aim_text(1, 10, 10)));
    EXPECT_EQ(target.kind, p::ContentKind::file);
    EXPECT_EQ(target.title, "Report");
    EXPECT_EQ(service->downloads().size(), 0u) << "an aim registers no download";

    const auto content = std::get<p::Content>(one(grab_text("g1", 10, 10)));
    EXPECT_EQ(content.kind, p::ContentKind::file);
    EXPECT_EQ(content.name, "report.pdf");
    EXPECT_EQ(content.mime, "application/pdf");
    EXPECT_EQ(content.size, static_cast<std::int64_t>(fs::file_size(report)));
    EXPECT_EQ(content.sha256, sha256_hex("%PDF-1.4 not really"));
    ASSERT_TRUE(content.download);
    EXPECT_EQ(content.download->rfind("/dl/", 0), 0u);
    EXPECT_GE(content.download->size(), 4u + 22u) << "at least 128 random bits";
    EXPECT_FALSE(content.download->find(report.string()) != std::string::npos) << "no path in the link";

    const auto checkout = service->downloads().begin(*content.download);
    ASSERT_TRUE(checkout);
    EXPECT_EQ(checkout->entry->file, report);
    EXPECT_EQ(checkout->entry->token, kContentToken) << "the link is bound to the session's token";
    service->downloads().end(*checkout, true);
    EXPECT_FALSE(service->downloads().begin(*content.download)) << "a link ends when its download completes";

    const auto url = std::get<p::Content>(one(grab_text("g2", 50, 5)));
    EXPECT_EQ(url.kind, p::ContentKind::url);
    EXPECT_EQ(url.url, "https://example.org/");
    EXPECT_FALSE(url.download);

    // Right half, lower part: no tile and nothing shared there.
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g3", 50, 30))).kind, p::ContentKind::none);
    // Off the field: not_found with the grab's id; the session goes on.
    const auto off = std::get<p::Error>(one(grab_text("g4", 70, 5)));
    EXPECT_EQ(off.code, p::ErrorCode::not_found);
    EXPECT_EQ(off.id, p::RequestId{std::string("g4")});
    EXPECT_EQ(std::get<p::Target>(one(aim_text(2, 70, 5))).kind, p::ContentKind::none);
}

TEST_F(ProviderContent, AFileGoneSinceTheBoardLoadedIsAnInternalError) {
    fs::remove(report);
    const auto e = std::get<p::Error>(one(grab_text("g1", 10, 10)));
    EXPECT_EQ(e.code, p::ErrorCode::internal);
    EXPECT_EQ(e.message, "cannot read report.pdf") << "the message names the file, not where it lives";
}

TEST_F(ProviderContent, SharedItemsComeAfterTheBoardAndOnTopOfEachOther) {
    SharedItem a;
    a.url = "https://a.example/";
    a.rect = {960, 540, 960, 540};
    const int first = shared->add(a);
    SharedItem b;
    b.file = report;
    b.title = "Shared report";
    b.rect = {1400, 800, 100, 100};
    shared->add(b);
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g1", 50, 30))).url, "https://a.example/");
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g2", 48, 28))).title, "Shared report");  // (1440, 840)
    // The board still wins where it has a tile.
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g3", 10, 10))).title, "Report");
    EXPECT_TRUE(shared->remove(first));
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g4", 50, 30))).kind, p::ContentKind::none);

    SharedItem bad;
    bad.file = dir.path / "missing.pdf";
    bad.rect = {0, 0, 10, 10};
    EXPECT_THROW(shared->add(bad), std::invalid_argument);
    SharedItem no_rect;
    no_rect.url = "https://a.example/";
    EXPECT_THROW(shared->add(no_rect), std::invalid_argument);
    SharedItem javascript;
    javascript.url = "javascript:alert(1)";
    javascript.rect = {0, 0, 10, 10};
    EXPECT_THROW(shared->add(javascript), std::invalid_argument);
}

TEST_F(ProviderContent, AimsAndGrabsAreRateLimited) {
    // 10 aims a second: a second's worth passes, the rest is dropped with one
    // error a second at most.
    int targets = 0, errors = 0, silent = 0;
    for (int i = 0; i < 40; ++i) {
        auto out = service->handle_text(state, aim_text(i, 10, 10), now);
        if (out.replies.empty()) ++silent;
        else if (std::holds_alternative<p::Target>(out.replies[0])) ++targets;
        else if (std::get<p::Error>(out.replies[0]).code == p::ErrorCode::rate_limited) ++errors;
    }
    EXPECT_EQ(targets, 10);
    EXPECT_EQ(errors, 1);
    EXPECT_EQ(silent, 29);
    now += 1s;
    EXPECT_TRUE(std::holds_alternative<p::Target>(one(aim_text(99, 10, 10))));

    // 30 grabs a minute, bursts of 6: the excess answered with its id.
    int contents = 0;
    for (int i = 0; i < 10; ++i) {
        const auto m = one(grab_text("g" + std::to_string(i), 50, 5));
        if (std::holds_alternative<p::Content>(m)) ++contents;
        else {
            EXPECT_EQ(std::get<p::Error>(m).code, p::ErrorCode::rate_limited);
            EXPECT_EQ(std::get<p::Error>(m).id, p::RequestId{"g" + std::to_string(i)});
        }
    }
    EXPECT_EQ(contents, 6);
    now += 2s;  // one more grab's worth
    EXPECT_TRUE(std::holds_alternative<p::Content>(one(grab_text("late", 50, 5))));
    EXPECT_TRUE(state.welcomed);
}

TEST_F(ProviderContent, WrongTokensAreLimitedPerAddress) {
    for (int i = 0; i < kMaxWrongTokens; ++i) {
        SessionState s;
        s.peer = "198.51.100.7";
        auto out = service->handle_text(s, p::encode(p::Hello{std::nullopt, "wrong-token-0123456789abc", "x"}), now);
        EXPECT_EQ(std::get<p::Error>(out.replies[0]).code, p::ErrorCode::unauthorized);
        EXPECT_TRUE(out.close);
    }
    // Even the right token is refused from that address for the rest of the minute...
    SessionState s;
    s.peer = "198.51.100.7";
    auto limited = service->handle_text(s, p::encode(p::Hello{std::nullopt, kContentToken, "x"}), now);
    EXPECT_EQ(std::get<p::Error>(limited.replies[0]).code, p::ErrorCode::rate_limited);
    EXPECT_FALSE(s.welcomed);
    // ...but not from another one, and not after the minute.
    SessionState other;
    other.peer = "198.51.100.8";
    service->handle_text(other, p::encode(p::Hello{std::nullopt, kContentToken, "x"}), now);
    EXPECT_TRUE(other.welcomed);
    service->handle_text(s, p::encode(p::Hello{std::nullopt, kContentToken, "x"}), now + kWrongTokenWindow);
    EXPECT_TRUE(s.welcomed);
}

// The screen's console hears of each refused hello, and of a flood once.
TEST_F(ProviderContent, RefusedHellosAreToldToTheActivityListenerOnceAFlood) {
    struct Refusals : ActivityListener {
        std::vector<RefusedActivity> seen;
        void seeking(std::uint64_t) override {}
        void aimed(const AimActivity&) override {}
        void left(std::uint64_t) override {}
        void refused(const RefusedActivity& r) override { seen.push_back(r); }
    };
    auto refusals = std::make_shared<Refusals>();
    service = std::make_unique<Service>(default_service_config(1920, 1080), kContentToken,
                                        std::vector<std::shared_ptr<const Resolver>>{}, nullptr, refusals);
    p::Hello hello{std::nullopt, "wrong-token-0123456789abc", "umf-web/0.1 (Android)"};
    hello.device = "Pixel 7";
    for (int i = 0; i < kMaxWrongTokens + 10; ++i) {
        SessionState s;
        s.peer = "198.51.100.7";
        service->handle_text(s, p::encode(hello), now);
    }
    ASSERT_EQ(refusals->seen.size(), static_cast<std::size_t>(kMaxWrongTokens) + 1);
    EXPECT_EQ(refusals->seen[0].client, "umf-web/0.1 (Android)");
    EXPECT_EQ(refusals->seen[0].device, "Pixel 7");
    EXPECT_EQ(refusals->seen[0].peer, "198.51.100.7");
    EXPECT_FALSE(refusals->seen[0].rate_limited);
    EXPECT_TRUE(refusals->seen.back().rate_limited);
    // The right token is no refusal.
    SessionState good;
    good.peer = "198.51.100.8";
    service->handle_text(good, p::encode(p::Hello{std::nullopt, kContentToken, "x"}), now);
    EXPECT_TRUE(good.welcomed);
    EXPECT_EQ(refusals->seen.size(), static_cast<std::size_t>(kMaxWrongTokens) + 1);
}

TEST_F(ProviderContent, PublicModeWelcomesAnyoneToTheBoardOnly) {
    Board board;
    board.items.push_back({"Report", report, std::nullopt, std::nullopt, std::nullopt});
    make_service(std::make_shared<BoardResolver>(board, std::vector<PixelRect>{{0, 0, 960, 1080}}), true);
    SessionState anyone;
    service->handle_text(anyone, p::encode(p::Hello{std::nullopt, "anything-at-all", "kiosk visitor"}), now);
    EXPECT_TRUE(anyone.welcomed);
    SharedItem a;
    a.url = "https://a.example/";
    a.rect = {960, 0, 960, 1080};
    shared->add(a);  // shared on the desktop, but not resolved in public mode
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g1", 50, 5))).kind, p::ContentKind::none);
    EXPECT_EQ(std::get<p::Content>(one(grab_text("g2", 10, 5))).kind, p::ContentKind::file);
}

// What an overlay would hear.
struct RecordingListener : ActivityListener {
    std::mutex mutex;
    std::vector<std::string> events;
    std::vector<AimActivity> aims;
    void seeking(std::uint64_t session) override {
        std::lock_guard lock(mutex);
        events.push_back("seeking " + std::to_string(session));
    }
    void aimed(const AimActivity& aim) override {
        std::lock_guard lock(mutex);
        events.push_back("aim " + std::to_string(aim.session));
        aims.push_back(aim);
    }
    void left(std::uint64_t session) override {
        std::lock_guard lock(mutex);
        events.push_back("left " + std::to_string(session));
    }
};

TEST_F(ProviderContent, TheOverlayHearsWhoSeeksAimsAndLeaves) {
    auto listener = std::make_shared<RecordingListener>();
    Board board;
    board.items.push_back({"Report", report, std::nullopt, std::nullopt, std::nullopt});
    Service s(default_service_config(1920, 1080), kContentToken,
              {std::make_shared<BoardResolver>(board, std::vector<PixelRect>{{0, 0, 960, 1080}})}, nullptr, listener);
    SessionState a, b, stranger;
    s.handle_text(a, p::encode(p::Hello{std::nullopt, kContentToken, "a"}), now);
    s.handle_text(b, p::encode(p::Hello{std::nullopt, kContentToken, "b"}), now);
    s.handle_text(stranger, p::encode(p::Hello{std::nullopt, "wrong-token-0123456789abcdef", "x"}), now);
    ASSERT_NE(a.id, b.id);
    s.handle_text(a, R"({"type":"seeking","v":1})", now);
    s.handle_text(b, aim_text(1, 10, 10), now);
    s.handle_text(b, aim_text(2, 70, 10), now);  // off the field
    s.session_ended(a);
    s.session_ended(stranger);  // never welcomed: nothing to tell
    s.session_ended(b);
    const std::string ia = std::to_string(a.id), ib = std::to_string(b.id);
    EXPECT_EQ(listener->events, (std::vector<std::string>{"seeking " + ia, "aim " + ib, "aim " + ib, "left " + ia,
                                                          "left " + ib}));
    ASSERT_EQ(listener->aims.size(), 2u);
    ASSERT_TRUE(listener->aims[0].screen);
    EXPECT_DOUBLE_EQ(listener->aims[0].screen->x, 300.0);
    EXPECT_EQ(listener->aims[0].title, "Report");
    EXPECT_DOUBLE_EQ(listener->aims[0].confidence, 0.9);
    EXPECT_FALSE(listener->aims[1].screen);
}

TEST(ProviderDownloads, LinksExpireAndTheTableStaysBounded) {
    DownloadTable table(std::chrono::seconds(60), 3);
    const auto t0 = DownloadTable::Clock::now();
    DownloadEntry e;
    e.name = "a.txt";
    e.bytes = std::make_shared<const std::string>("abc");
    const std::string late = table.add(e, t0);
    EXPECT_FALSE(table.begin(late, t0 + std::chrono::seconds(61))) << "expired";
    const std::string fresh = table.add(e, t0);
    const auto checkout = table.begin(fresh + "?x=1", t0 + std::chrono::seconds(59));
    ASSERT_TRUE(checkout);
    table.end(*checkout, true);
    for (const char* bad : {"/dl/", "/dl", "/dl/../x", "/index.html", ""}) EXPECT_FALSE(table.begin(bad, t0)) << bad;
    std::vector<std::string> links;
    for (int i = 0; i < 5; ++i) links.push_back(table.add(e, t0 + std::chrono::seconds(i)));
    EXPECT_EQ(table.size(), 3u);
    EXPECT_FALSE(table.begin(links[0], t0 + std::chrono::seconds(5))) << "the oldest made room";
    EXPECT_TRUE(table.begin(links[4], t0 + std::chrono::seconds(5)));
}

// A file too large to hash on the server's thread is answered from the
// hashing thread when it is done, and even its first content carries the
// SHA-256 (the download checks what it sends against it).
TEST_F(ProviderContent, ALargeFileIsAnsweredWithItsHashOnceHashed) {
    const fs::path large = dir.path / "large.bin";
    { std::ofstream(large) << "x"; }
    fs::resize_file(large, static_cast<std::uintmax_t>(kHashAtOnceBytes) + 1);
    SharedItem item;
    item.file = large;
    item.rect = {960, 540, 960, 540};
    shared->add(item);
    std::mutex mutex;
    std::condition_variable arrived;
    std::vector<std::string> pushed;
    SessionState pushing;
    pushing.outbox = [&](std::uint64_t, std::string message) {
        std::lock_guard lock(mutex);
        pushed.push_back(std::move(message));
        arrived.notify_all();
    };
    service->handle_text(pushing, p::encode(p::Hello{std::nullopt, kContentToken, "test"}), now);
    ASSERT_TRUE(pushing.welcomed);
    const auto out = service->handle_text(pushing, grab_text("big", 50, 30), now);
    EXPECT_TRUE(out.replies.empty()) << "the grab did not wait on the server's thread";
    std::unique_lock lock(mutex);
    ASSERT_TRUE(arrived.wait_for(lock, std::chrono::seconds(20), [&] { return !pushed.empty(); }))
        << "the content never came";
    const auto parsed = p::parse_message(pushed.at(0), p::kRequesterLimits);
    const auto& content = std::get<p::Content>(std::get<p::Message>(parsed));
    EXPECT_EQ(content.id, p::RequestId{std::string("big")});
    EXPECT_EQ(content.size, kHashAtOnceBytes + 1);
    ASSERT_TRUE(content.sha256);
    EXPECT_EQ(content.sha256->size(), 64u);
    lock.unlock();
    // Known now: the next grab is answered at once with the same hash.
    now += std::chrono::seconds(3);
    const auto again = std::get<p::Content>(one(grab_text("again", 50, 30)));
    EXPECT_EQ(again.sha256, content.sha256);
}

TEST(ProviderDownloads, FileFacts) {
    TempDir dir;
    const fs::path f = dir.path / "x.CSV";
    std::ofstream(f) << "abc";
    FileFactsCache cache;
    const auto facts = cache.facts(f);
    EXPECT_EQ(facts.size, 3);
    EXPECT_EQ(facts.sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(mime_for(f), "text/csv");
    EXPECT_EQ(mime_for("noext"), "application/octet-stream");
    EXPECT_THROW(cache.facts(dir.path), std::runtime_error);
    EXPECT_THROW(cache.facts(dir.path / "missing"), std::runtime_error);
    // A changed file is hashed again.
    std::ofstream(f) << "abcd";
    EXPECT_EQ(cache.facts(f).size, 4);
    // Rewritten in place with its old time and size: the cache cannot tell
    // until told (a download that found the bytes changed forgets it).
    const auto before = cache.facts(f);
    const auto mtime = fs::last_write_time(f);
    std::ofstream(f) << "abce";
    fs::last_write_time(f, mtime);
    EXPECT_EQ(cache.facts(f).sha256, before.sha256);
    cache.forget(f);
    EXPECT_NE(cache.facts(f).sha256, before.sha256);
    EXPECT_EQ(cache.facts(f).identity, before.identity);
}

TEST(ProviderControl, RequestsShareListAndUnshare) {
    TempDir dir;
    const fs::path file = dir.path / "a.txt";
    std::ofstream(file) << "a";
    auto items = std::make_shared<SharedItems>();
    ControlSocket socket(dir.path / "sock" / "provider-1.sock", items);
    const std::string shared = control_request(
        socket.path(), R"({"cmd":"share","file":")" + file.string() + R"(","rect":[0,0,100,100],"title":"A"})");
    EXPECT_EQ(shared, R"({"id":1,"ok":true})");
    EXPECT_NE(control_request(socket.path(), R"({"cmd":"list"})").find("\"title\":\"A\""), std::string::npos);
    EXPECT_EQ(control_request(socket.path(), R"({"cmd":"unshare","id":1})"), R"({"ok":true})");
    EXPECT_TRUE(items->items().empty());
    for (const char* bad : {"not json", R"({"cmd":"share","url":"https://x/"})", R"({"cmd":"share","url":"ftp://x/","rect":[0,0,1,1]})",
                            R"({"cmd":"share","file":"/nonexistent/x","rect":[0,0,1,1]})", R"({"cmd":"format-disk"})",
                            R"({"cmd":"unshare","id":99})", R"([1,2])"}) {
        const std::string answer = control_request(socket.path(), bad);
        EXPECT_EQ(answer.rfind(R"({"error":)", 0), 0u) << bad << " -> " << answer;
        EXPECT_NE(answer.find(R"("ok":false)"), std::string::npos) << bad;
    }
    // A second provider cannot take over a socket that answers.
    EXPECT_THROW(ControlSocket(socket.path(), items), std::runtime_error);
}

TEST(ProviderPairingQr, DrawsTheWholeCodeWithAQuietZone) {
    const std::string url = "https://192.168.1.20:47470/#t=2P8PS1OkkJ6N7t191DIZPnPoi7GaecUS&fp=" + std::string(64, 'a');
    const auto modules = qr_modules(url);
    const std::size_t n = modules.size();
    EXPECT_GE(n, 41u);  // version 6 or more for about 140 bytes at level M
    EXPECT_EQ((n - 17) % 4, 0u);
    // Finder patterns in three corners.
    for (auto [y, x] : {std::pair<std::size_t, std::size_t>{0, 0}, {0, n - 7}, {n - 7, 0}}) {
        EXPECT_TRUE(modules[y][x]);
        EXPECT_TRUE(modules[y + 3][x + 3]);
        EXPECT_FALSE(modules[y + 1][x + 1]);
    }
    const std::string text = qr_text(url);
    std::size_t lines = 0;
    for (char c : text) lines += c == '\n';
    EXPECT_EQ(lines, (n + 4 + 1) / 2);
    EXPECT_THROW(qr_modules(std::string(8000, 'x')), std::runtime_error);
}

}  // namespace

#endif
