// Puts without sockets (docs/PROTOCOL.md, "Put"): the service's checks and
// their order, the decider asked or not, answers pushed to the session's
// outbox later, timeouts, trusted devices, sessions that leave; the upload
// link table and the file sink; the HTTPS transport's poll hearing a push.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include "shared/io/unique_name.hpp"

#include <boost/asio/io_context.hpp>
#include <nlohmann/json.hpp>

#include "provider/content/file_facts.hpp"
#include "provider/net/api_sessions.hpp"
#include "provider/put/put_desk.hpp"
#include "provider/put/trusted_devices.hpp"
#include "provider/put/upload_sink.hpp"
#include "provider/put/upload_table.hpp"
#include "provider/service/service.hpp"
#include "shared/protocol/json_checks.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/provider/put_test_support.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
namespace p = umf::protocol;
using namespace umf::provider;
using umf::test::FakeXdgOpen;
using umf::test::folder_names;
using umf::test::ScriptedDecider;
using umf::test::TempDir;
using umf::test::file_put;
using umf::test::url_put;

constexpr const char* kPutServiceToken = "put-token-0123456789abcdefgh";

std::string put_hello(const std::optional<std::string>& device = std::nullopt) {
    return p::encode(p::Hello{p::RequestId{std::int64_t{1}}, kPutServiceToken, "Pixel 7", device});
}

class PutService : public ::testing::Test {
protected:
    TempDir dir;
    fs::path folder = dir.path / "Downloads";
    FakeXdgOpen xdg{dir.path / "bin"};  // never the desktop's own
    std::shared_ptr<ScriptedDecider> decider = std::make_shared<ScriptedDecider>();
    std::unique_ptr<Service> service;
    SessionState state;
    std::mutex mutex;
    std::condition_variable pushed_cv;
    std::vector<std::string> pushed;  // what the session's outbox got

    std::function<bool(const ScreenPoint&, const std::string&)> open_url_at;

    void make(std::shared_ptr<PutDecider> d, std::chrono::milliseconds timeout = std::chrono::seconds(30),
              std::int64_t max_bytes = std::int64_t{4} << 30) {
        ServiceConfig config = default_service_config();
        config.puts.open_url_at = open_url_at;
        config.put_decider = std::move(d);
        config.puts.folder = folder;
        config.puts.answer_timeout = timeout;
        config.puts.max_bytes = max_bytes;
        config.puts.trusted_devices = dir.path / "cfg" / kTrustedDevicesFile;
        service = std::make_unique<Service>(std::move(config), kPutServiceToken);
    }
    void SetUp() override { make(decider); }
    p::Welcome welcome(SessionState& s, const std::optional<std::string>& device = std::nullopt) {
        s.outbox = [this](std::uint64_t, std::string message) {
            std::lock_guard lock(mutex);
            pushed.push_back(std::move(message));
            pushed_cv.notify_all();
        };
        auto out = service->handle_text(s, put_hello(device));
        EXPECT_EQ(out.replies.size(), 1u);
        return std::get<p::Welcome>(out.replies.at(0));
    }
    p::Message put(SessionState& s, const p::Put& m) {
        auto out = service->handle_text(s, p::encode(m));
        EXPECT_EQ(out.replies.size(), 1u);
        EXPECT_FALSE(out.close);
        return out.replies.at(0);
    }
    // The n-th pushed message (0-based), waiting up to 5 s for it.
    std::optional<p::Message> push(std::size_t n = 0, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
        std::unique_lock lock(mutex);
        if (!pushed_cv.wait_for(lock, timeout, [&] { return pushed.size() > n; })) return std::nullopt;
        return std::get<p::Message>(p::parse_message(pushed[n], p::kRequesterLimits));
    }
    std::size_t push_count() {
        std::lock_guard lock(mutex);
        return pushed.size();
    }
};

p::ErrorCode code(const p::Message& m) {
    const auto* e = std::get_if<p::Error>(&m);
    EXPECT_NE(e, nullptr) << p::type_name(m);
    return e ? e->code : p::ErrorCode::internal;
}

const p::PutStatus& status(const p::Message& m) {
    static const p::PutStatus none{};
    const auto* s = std::get_if<p::PutStatus>(&m);
    EXPECT_NE(s, nullptr) << p::type_name(m) << (std::holds_alternative<p::Error>(m) ? ": " + std::get<p::Error>(m).message : "");
    return s ? *s : none;
}

TEST_F(PutService, WithoutADeciderTheWelcomeOffersNoPutAndPutsAreRefused) {
    make(nullptr);
    EXPECT_TRUE(welcome(state).features.empty());
    EXPECT_EQ(code(put(state, url_put())), p::ErrorCode::refused);
    EXPECT_EQ(std::get<p::Error>(put(state, url_put())).id, p::RequestId{std::string("p1")});
}

TEST_F(PutService, TheWelcomeNamesPutAndThePutAsksTheScreen) {
    EXPECT_EQ(welcome(state, "phone-1").features, (std::vector<std::string>{"put", "put-hash-after"}));
    const auto reply = put(state, url_put());
    EXPECT_EQ(status(reply).status, p::PutState::asking);
    EXPECT_EQ(status(reply).id, p::RequestId{std::string("p1")});
    const auto offers = decider->offers(1);
    ASSERT_EQ(offers.size(), 1u);
    EXPECT_EQ(offers[0].client, "Pixel 7");
    EXPECT_EQ(offers[0].device, "phone-1");
    EXPECT_EQ(offers[0].kind, p::ContentKind::url);
    EXPECT_EQ(offers[0].url, "https://example.org/talk");
    EXPECT_EQ(offers[0].title, "Talk page");
    ASSERT_TRUE(offers[0].at);
    EXPECT_EQ(offers[0].at->screen, 0);
}

TEST_F(PutService, AnAcceptedUrlOpensInTheBrowserAndIsPushedAsDone) {
    welcome(state);
    put(state, url_put());
    const auto offer = decider->offers(1).at(0);
    EXPECT_EQ(push_count(), 0u);
    // Answered later, from another thread.
    std::thread([&] { decider->answer(offer.id, {PutAnswer::save, false}); }).join();
    const auto pushed = push();
    ASSERT_TRUE(pushed);
    EXPECT_EQ(status(*pushed).status, p::PutState::done);
    EXPECT_EQ(status(*pushed).outcome, p::PutOutcome::opened);
    EXPECT_EQ(status(*pushed).id, p::RequestId{std::string("p1")});
    EXPECT_EQ(xdg.opened(), std::vector<std::string>{"https://example.org/talk"});
    // A second answer is ignored.
    decider->answer(offer.id, {PutAnswer::dismiss, false});
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_EQ(push_count(), 1u);
}

TEST_F(PutService, AUrlPutOnABrowserWindowOpensThereAndNotThroughXdgOpen) {
    std::vector<std::pair<double, std::string>> opened_in_place;
    bool browser_there = true;
    open_url_at = [&](const ScreenPoint& at, const std::string& url) {
        if (!browser_there) return false;
        opened_in_place.emplace_back(at.x, url);
        return true;
    };
    make(decider);
    welcome(state);
    put(state, url_put());
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, false});
    const auto pushed = push();
    ASSERT_TRUE(pushed);
    EXPECT_EQ(status(*pushed).outcome, p::PutOutcome::opened);
    ASSERT_EQ(opened_in_place.size(), 1u);
    EXPECT_EQ(opened_in_place[0].second, "https://example.org/talk");
    EXPECT_TRUE(xdg.opened(1, std::chrono::milliseconds(300)).empty());
    // No browser window there: the desktop's default opens it.
    browser_there = false;
    put(state, url_put());
    decider->answer(decider->offers(2).at(1).id, {PutAnswer::save, false});
    ASSERT_TRUE(push(1));
    EXPECT_EQ(xdg.opened(), std::vector<std::string>{"https://example.org/talk"});
}

TEST_F(PutService, AnAcceptedFileGetsASingleUseUploadLink) {
    welcome(state);
    put(state, file_put("hello"));
    const auto offer = decider->offers(1).at(0);
    EXPECT_EQ(offer.kind, p::ContentKind::file);
    EXPECT_EQ(offer.name, "report.pdf");
    EXPECT_EQ(offer.mime, "application/pdf");
    EXPECT_EQ(offer.size, 5);
    decider->answer(offer.id, {PutAnswer::open, false});
    const auto pushed = push();
    ASSERT_TRUE(pushed);
    const auto& s = status(*pushed);
    EXPECT_EQ(s.status, p::PutState::upload);
    ASSERT_TRUE(s.upload);
    EXPECT_EQ(s.upload->rfind("/up/", 0), 0u);
    EXPECT_EQ(s.upload->size(), 4u + 22u);
    auto checkout = service->puts().begin_upload(*s.upload);
    ASSERT_TRUE(checkout);
    const UploadEntry& entry = checkout->entry;
    EXPECT_EQ(entry.size, 5);
    EXPECT_EQ(entry.sha256, sha256_hex("hello"));
    EXPECT_TRUE(entry.open);
    EXPECT_EQ(entry.folder, folder);
    EXPECT_EQ(entry.session, state.id);
    service->puts().end_upload(*checkout, UploadEnd::stored);
    EXPECT_FALSE(service->puts().begin_upload(*s.upload)) << "a stored upload ends the link";
}

TEST_F(PutService, ADeciderThatAnswersAtOnceIsTheReplyItself) {
    make(std::make_shared<ScriptedDecider>(ScriptedDecider::Mode::at_once));
    welcome(state);
    const auto reply = put(state, file_put("x"));
    EXPECT_EQ(status(reply).status, p::PutState::upload) << "no asking when nobody is asked";
    EXPECT_EQ(push_count(), 0u);
}

TEST_F(PutService, ADismissIsRefusedAndLeavesNoLink) {
    welcome(state);
    put(state, file_put("hello"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::dismiss, true});
    const auto pushed = push();
    ASSERT_TRUE(pushed);
    EXPECT_EQ(code(*pushed), p::ErrorCode::refused);
    EXPECT_EQ(std::get<p::Error>(*pushed).id, p::RequestId{std::string("p2")});
    EXPECT_EQ(service->puts().uploads_waiting(), 0u);
    EXPECT_TRUE(folder_names(folder).empty());
}

TEST_F(PutService, NoAnswerInTimeIsWithdrawnAndRefused) {
    make(decider, std::chrono::milliseconds(200));
    welcome(state);
    const auto start = std::chrono::steady_clock::now();
    put(state, url_put());
    const auto offer = decider->offers(1).at(0);
    const auto pushed = push(0, std::chrono::seconds(5));
    ASSERT_TRUE(pushed);
    EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(190));
    EXPECT_EQ(code(*pushed), p::ErrorCode::refused);
    EXPECT_TRUE(decider->withdrawn(offer.id));
    EXPECT_EQ(service->puts().offers_waiting(), 0u);
    // An answer after the timeout changes nothing.
    EXPECT_TRUE(decider->answer(offer.id, {PutAnswer::save, false}));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_EQ(push_count(), 1u);
}

TEST_F(PutService, TooLargeIsRefusedBeforeAnyoneIsAsked) {
    make(decider, std::chrono::seconds(30), 1000);
    welcome(state);
    EXPECT_EQ(code(put(state, file_put(std::string(1001, 'x')))), p::ErrorCode::too_large);
    // Within the limit, but more than any disk has free.
    make(decider, std::chrono::seconds(30), std::numeric_limits<std::int64_t>::max());
    SessionState other;
    welcome(other);
    p::Put huge = file_put("x");
    huge.size = p::kMaxSafeInteger;
    const auto reply = put(other, huge);
    EXPECT_EQ(code(reply), p::ErrorCode::too_large);
    EXPECT_NE(std::get<p::Error>(reply).message.find("free"), std::string::npos);
    EXPECT_TRUE(decider->offers(0).empty());
}

TEST_F(PutService, APointOffEveryScreenIsNotFound) {
    welcome(state);
    EXPECT_EQ(code(put(state, url_put("p", {500, 500}))), p::ErrorCode::not_found);
    EXPECT_TRUE(decider->offers(0).empty());
}

TEST_F(PutService, PutsShareTheGrabsRateLimit) {
    welcome(state);
    int limited = 0;
    for (int i = 0; i < 10; ++i) {
        const p::Message reply = put(state, url_put("p" + std::to_string(i)));
        if (const auto* e = std::get_if<p::Error>(&reply)) limited += e->code == p::ErrorCode::rate_limited;
    }
    EXPECT_EQ(limited, 4) << "bursts of 6 of the default 30 a minute";
}

TEST_F(PutService, BeforeTheWelcomeAPutIsUnauthorized) {
    auto out = service->handle_text(state, p::encode(url_put()));
    ASSERT_EQ(out.replies.size(), 1u);
    EXPECT_EQ(code(out.replies[0]), p::ErrorCode::unauthorized);
    EXPECT_TRUE(out.close);
    SessionState wrong;
    out = service->handle_text(wrong, p::encode(p::Hello{std::nullopt, "wrong-token-0123456789abcdef", "x"}));
    EXPECT_TRUE(out.close);
    EXPECT_TRUE(decider->offers(0).empty());
}

TEST_F(PutService, APutStatusFromTheRequesterIsABadRequest) {
    welcome(state);
    auto out = service->handle_text(state, R"({"type":"put_status","v":1,"id":"p","status":"asking"})");
    EXPECT_EQ(code(out.replies.at(0)), p::ErrorCode::bad_request);
    EXPECT_FALSE(out.close);
}

TEST_F(PutService, ATrustedDeviceIsNotAskedAgainAndStaysTrusted) {
    welcome(state, "phone-1");
    put(state, file_put("a"));
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, true});
    ASSERT_TRUE(push());
    EXPECT_EQ(status(*push()).status, p::PutState::upload);
    const auto second = put(state, file_put("b", "p3"));
    EXPECT_EQ(status(second).status, p::PutState::upload) << "accepted at once";
    EXPECT_EQ(decider->offers(0).size(), 1u) << "not asked the second time";
    // Kept in the config dir, atomically written.
    const std::string text = umf::test::file_text(dir.path / "cfg" / kTrustedDevicesFile);
    const auto doc = nlohmann::json::parse(text);
    EXPECT_EQ(doc["devices"], nlohmann::json::array({"phone-1"}));
    TrustedDevices reloaded(dir.path / "cfg" / kTrustedDevicesFile);
    EXPECT_TRUE(reloaded.contains("phone-1"));
    EXPECT_FALSE(reloaded.contains("phone-2"));
    // Another device, or none, is still asked.
    SessionState other;
    welcome(other);
    put(other, url_put());
    EXPECT_EQ(decider->offers(2).size(), 2u);
}

TEST_F(PutService, AlwaysWithoutADeviceRemembersNothing) {
    welcome(state);
    put(state, url_put());
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, true});
    ASSERT_TRUE(push());
    EXPECT_FALSE(fs::exists(dir.path / "cfg" / kTrustedDevicesFile));
}

TEST_F(PutService, ASessionThatLeavesWithdrawsItsOffers) {
    welcome(state);
    put(state, url_put("a"));
    put(state, file_put("b", "b"));
    const auto offers = decider->offers(2);
    SessionState other;
    welcome(other);
    put(other, url_put("c"));
    service->session_ended(state);
    EXPECT_TRUE(decider->withdrawn(offers.at(0).id));
    EXPECT_TRUE(decider->withdrawn(offers.at(1).id));
    EXPECT_EQ(decider->withdrawn_count(), 2u) << "the other session's offer stays";
    EXPECT_EQ(service->puts().offers_waiting(), 1u);
    // A late answer to a withdrawn offer goes nowhere.
    decider->answer(offers.at(0).id, {PutAnswer::save, false});
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_EQ(push_count(), 0u);
}

TEST(PutUploadTable, ALinkLastsUntilItsUploadIsStoredOrAbandoned) {
    using namespace std::chrono_literals;
    UploadTable table(100ms, 2);
    const auto now = UploadTable::Clock::now();
    UploadEntry e;
    e.name = "a";
    const std::string a = table.add(e, now), b = table.add(e, now);
    EXPECT_NE(a, b);
    auto checkout = table.begin(a + "?x=1", now);
    ASSERT_TRUE(checkout);
    table.end(*checkout, UploadEnd::stored, now);
    EXPECT_FALSE(table.begin(a, now)) << "stored: the link ended";
    EXPECT_FALSE(table.begin("/dl/" + b.substr(4), now));
    EXPECT_FALSE(table.begin(b, now + 100ms)) << "a link nobody used expires";
    const std::string c = table.add(e, now), d = table.add(e, now + 1ms), f = table.add(e, now + 2ms);
    EXPECT_FALSE(table.begin(c, now)) << "the oldest made room";
    EXPECT_TRUE(table.begin(d, now));
    EXPECT_TRUE(table.begin(f, now));
}

// A broken upload keeps its sink with the link; nobody going on with it,
// it is abandoned and handed out once, for its session to be told.
TEST(PutUploadTable, ABrokenUploadWaitsForTheRestThenIsAbandoned) {
    using namespace std::chrono_literals;
    umf::test::TempDir dir;
    UploadTable table(100ms, 4);
    const auto now = UploadTable::Clock::now();
    UploadEntry e;
    e.name = "a.bin";
    e.size = 10;
    e.sha256 = sha256_hex("0123456789");
    e.folder = dir.path;
    const std::string link = table.add(e, now);
    auto first = table.begin(link, now);
    ASSERT_TRUE(first);
    EXPECT_FALSE(first->sink);
    auto sink = table.keep_sink(*first, std::make_shared<UploadSink>(e.folder, e.size, e.sha256));
    const auto claim = sink->claim();
    sink->write("01234", 5, claim.claim);
    table.end(*first, UploadEnd::broken, now + 50ms);
    EXPECT_FALSE(table.next_abandon() < now + 150ms) << "the lifetime counts from the break";

    auto second = table.begin(link, now + 140ms);
    ASSERT_TRUE(second) << "the rest may come within the lifetime";
    ASSERT_EQ(second->sink, sink);
    const auto again = sink->claim();
    EXPECT_EQ(again.received, 5);
    EXPECT_THROW(sink->write("x", 1, claim.claim), UploadError) << "the older request was superseded";
    EXPECT_TRUE(sink->superseded(claim.claim));
    table.end(*second, UploadEnd::broken, now + 150ms);
    EXPECT_TRUE(table.take_abandoned(now + 200ms).empty());
    const auto abandoned = table.take_abandoned(now + 260ms);
    ASSERT_EQ(abandoned.size(), 1u);
    EXPECT_EQ(abandoned[0].received, 5);
    EXPECT_EQ(abandoned[0].entry.name, "a.bin");
    EXPECT_FALSE(table.begin(link, now + 260ms));
    EXPECT_TRUE(table.take_abandoned(now + 300ms).empty());
}

TEST(PutUploadSink, StoresOnlyWhatMatchesAndNeverOverwrites) {
    TempDir dir;
    const std::string bytes = "the bytes of the file";
    {
        UploadSink sink(dir.path, static_cast<std::int64_t>(bytes.size()), sha256_hex(bytes));
        EXPECT_EQ(sink.temp_path().filename().string().rfind(".umf-put-", 0), 0u);
        struct stat st {};
        ASSERT_EQ(::stat(sink.temp_path().c_str(), &st), 0);
        EXPECT_EQ(st.st_mode & 0777, 0600u);
        sink.write(bytes.data(), 5);
        sink.write(bytes.data() + 5, bytes.size() - 5);
        EXPECT_EQ(sink.store("notes.txt"), "notes.txt");
    }
    {
        UploadSink sink(dir.path, static_cast<std::int64_t>(bytes.size()), sha256_hex(bytes));
        sink.write(bytes.data(), bytes.size());
        EXPECT_EQ(sink.store("notes.txt"), "notes (1).txt");
    }
    EXPECT_EQ(folder_names(dir.path), (std::vector<std::string>{"notes (1).txt", "notes.txt"}));
    {
        UploadSink sink(dir.path, static_cast<std::int64_t>(bytes.size()), sha256_hex("other"));
        sink.write(bytes.data(), bytes.size());
        try {
            sink.store("bad.txt");
            ADD_FAILURE() << "a wrong hash was stored";
        } catch (const UploadError& e) {
            EXPECT_EQ(e.code(), p::ErrorCode::interrupted);
        }
    }
    {
        UploadSink sink(dir.path, 10, sha256_hex("0123456789"));
        sink.write("01234", 5);
        EXPECT_THROW(sink.store("short.txt"), UploadError);
    }
    {
        UploadSink sink(dir.path, 3, sha256_hex("abc"));
        EXPECT_THROW(sink.write("abcd", 4), UploadError) << "more than the size";
        sink.write("ab", 2);
    }  // dropped half way
    EXPECT_EQ(folder_names(dir.path), (std::vector<std::string>{"notes (1).txt", "notes.txt"}));
    EXPECT_EQ(umf::test::file_text(dir.path / "notes.txt"), bytes);
    EXPECT_THROW(UploadSink(dir.path, p::kMaxSafeInteger, std::string(64, '0')), UploadError);
    EXPECT_EQ(umf::io::numbered_name("report.pdf", 2), "report (2).pdf");
    EXPECT_EQ(umf::io::numbered_name(".bashrc", 1), ".bashrc (1)");
    EXPECT_EQ(umf::io::numbered_name(std::string(300, 'a') + ".txt", 1).size(), 255u);
}

TEST(PutApiSessions, APushedAnswerReachesTheLongPoll) {
    TempDir dir;
    auto decider = std::make_shared<ScriptedDecider>();
    ServiceConfig config = default_service_config();
    config.put_decider = decider;
    config.puts.folder = dir.path;
    auto service = std::make_shared<Service>(std::move(config), kPutServiceToken);
    boost::asio::io_context io;
    auto sessions = ApiSessions::create(io.get_executor(), service);
    const auto welcomed = sessions->hello(put_hello(), "127.0.0.1");
    ASSERT_EQ(welcomed.status, 200);
    const auto body = nlohmann::json::parse(welcomed.body);
    const std::string id = body["session"];
    EXPECT_EQ(body["messages"][0]["features"], nlohmann::json::array({"put", "put-hash-after"}));
    const auto asked = sessions->message(id, p::encode(url_put()));
    EXPECT_EQ(nlohmann::json::parse(asked.body)["messages"][0]["status"], "asking");

    std::optional<ApiSessions::Reply> heard;
    const auto start = sessions->begin_poll(id, [&](ApiSessions::Reply r) { heard = std::move(r); });
    ASSERT_FALSE(start.now);
    FakeXdgOpen xdg(dir.path / "bin");
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, false});
    ASSERT_TRUE(heard);
    const auto polled = nlohmann::json::parse(heard->body);
    EXPECT_EQ(polled["messages"][0]["type"], "put_status");
    EXPECT_EQ(polled["messages"][0]["outcome"], "opened");
    EXPECT_EQ(polled["messages"][0]["id"], "p1");

    // The session's end withdraws what it still waits for.
    sessions->message(id, p::encode(url_put("p9")));
    const auto offer = decider->offers(2).at(1);
    sessions->close(id);
    EXPECT_TRUE(decider->withdrawn(offer.id));
    sessions->stop();
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
