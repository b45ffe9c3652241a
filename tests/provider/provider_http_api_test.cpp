// The protocol over plain HTTPS requests (docs/PROTOCOL.md, "HTTPS
// transport"), with curl as an independent client against a real server:
// hello, messages, the long poll, expiry, the session cap, closing, and what
// is refused (wrong content type, large bodies, unknown sessions).
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "provider/content/board_resolver.hpp"
#include "provider/net/api_sessions.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using umf::test::run_command;
using umf::test::TempDir;
namespace fs = std::filesystem;
namespace p = umf::protocol;
using namespace umf::provider;
using json = nlohmann::json;
using namespace std::chrono_literals;

constexpr const char* kApiToken = "http-api-test-token-0123456789";

struct Call {
    std::string method = "POST";
    std::string path;
    std::string body;
    std::string content_type = "application/json";  // empty: no Content-Type at all
};

struct ApiResponse {
    int status = 0;
    std::string raw;
    std::string headers;
    json body;  // null when not JSON
    std::vector<p::Message> messages() const {
        std::vector<p::Message> out;
        if (!body.is_object() || !body.contains("messages")) return out;
        for (const auto& m : body["messages"]) {
            auto parsed = p::parse_message(m.dump(), p::kRequesterLimits);
            if (auto* message = std::get_if<p::Message>(&parsed))
                out.push_back(*message);
            else
                ADD_FAILURE() << "a message does not parse: " << m.dump();
        }
        return out;
    }
    int closed() const { return body.is_object() && body.contains("closed") ? body["closed"].get<int>() : 0; }
    std::string session() const {
        return body.is_object() && body.contains("session") ? body["session"].get<std::string>() : "";
    }
};

class ApiRecorder : public ActivityListener {
public:
    void seeking(std::uint64_t) override {}
    void aimed(const AimActivity&) override {}
    void left(std::uint64_t session) override {
        std::lock_guard lock(mutex_);
        left_.push_back(session);
    }
    std::size_t left_count() {
        std::lock_guard lock(mutex_);
        return left_.size();
    }

private:
    std::mutex mutex_;
    std::vector<std::uint64_t> left_;
};

std::string api_hello(const std::string& token = kApiToken) {
    return p::encode(p::Hello{p::RequestId{std::int64_t{1}}, token, "provider_http_api_test"});
}

class ProviderHttpApi : public ::testing::Test {
protected:
    TempDir dir;
    fs::path doc;
    std::shared_ptr<ApiRecorder> recorder = std::make_shared<ApiRecorder>();
    std::shared_ptr<Service> service;
    std::unique_ptr<Server> server;
    std::atomic<int> calls{0};

    static void SetUpTestSuite() {
        if (run_command("curl --version >/dev/null 2>&1").exit_code != 0) GTEST_SKIP() << "curl is not installed";
    }
    void start(ApiSessionOptions options = {}) {
        doc = dir.path / "report.txt";
        std::ofstream(doc) << "the report\n";
        Board board;
        board.items.push_back({"Report", doc, std::nullopt, std::nullopt, std::nullopt});
        auto resolver = std::make_shared<BoardResolver>(board, std::vector<PixelRect>{{0, 0, 1920, 1080}});
        service = std::make_shared<Service>(default_service_config(), kApiToken,
                                            std::vector<std::shared_ptr<const Resolver>>{resolver}, nullptr, recorder);
        ServerOptions server_options;
        server_options.api_sessions = options;
        server = make_server(service, load_or_create_tls_identity(dir.path / "cfg"), server_options);
        server->start();
    }
    std::string url(const std::string& path) const {
        return "https://127.0.0.1:" + std::to_string(server->port()) + path;
    }
    // One curl for all calls (--next), so they share a kept-alive connection.
    std::vector<ApiResponse> curl_many(const std::vector<Call>& list, const std::string& options = "") {
        std::string command = "curl";
        const int batch = calls++;
        for (std::size_t i = 0; i < list.size(); ++i) {
            const Call& c = list[i];
            const std::string stem = (dir.path / ("c" + std::to_string(batch) + "-" + std::to_string(i))).string();
            if (i) command += " --next";
            command += " -s -k --path-as-is --max-time 20 " + options + " -X " + c.method + " -o '" + stem +
                       ".out' -D '" + stem + ".headers' -w '%{http_code}\\n'";
            if (c.method == "POST") {
                std::ofstream(stem + ".in", std::ios::binary) << c.body;
                command += " --data-binary @'" + stem + ".in' -H 'Content-Type:" +
                           (c.content_type.empty() ? "" : " " + c.content_type) + "'";
            }
            command += " '" + url(c.path) + "'";
        }
        const auto r = run_command(command);
        std::vector<ApiResponse> out;
        std::size_t at = 0;
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string stem = (dir.path / ("c" + std::to_string(batch) + "-" + std::to_string(i))).string();
            ApiResponse res;
            const auto end = r.out.find('\n', at);
            if (end != std::string::npos) {
                res.status = std::atoi(r.out.substr(at, end - at).c_str());
                at = end + 1;
            }
            std::ifstream b(stem + ".out", std::ios::binary), h(stem + ".headers");
            res.raw.assign(std::istreambuf_iterator<char>(b), {});
            res.headers.assign(std::istreambuf_iterator<char>(h), {});
            res.body = json::parse(res.raw, nullptr, false);
            if (res.body.is_discarded()) res.body = nullptr;
            out.push_back(std::move(res));
        }
        return out;
    }
    ApiResponse call(const Call& c, const std::string& options = "") { return curl_many({c}, options).at(0); }
    ApiResponse post(const std::string& path, const std::string& body) { return call({"POST", path, body}); }
    ApiResponse poll(const std::string& session, const std::string& options = "") {
        return call({"GET", "/api/session/" + session + "/events", ""}, options);
    }
    std::string welcome() {
        const ApiResponse r = post("/api/hello", api_hello());
        EXPECT_EQ(r.status, 200) << r.raw;
        const auto messages = r.messages();
        EXPECT_TRUE(messages.size() == 1 && std::holds_alternative<p::Welcome>(messages[0])) << r.raw;
        EXPECT_EQ(r.closed(), 0);
        return r.session();
    }
    template <class Predicate>
    static bool eventually(Predicate done, std::chrono::milliseconds limit = 5s) {
        const auto deadline = std::chrono::steady_clock::now() + limit;
        while (!done()) {
            if (std::chrono::steady_clock::now() > deadline) return false;
            std::this_thread::sleep_for(10ms);
        }
        return true;
    }
};

TEST_F(ProviderHttpApi, HelloAimGrabAndTheDownload) {
    start();
    const ApiResponse r = post("/api/hello", api_hello());
    ASSERT_EQ(r.status, 200) << r.raw;
    const std::string session = r.session();
    ASSERT_EQ(session.size(), 32u) << r.raw;
    EXPECT_EQ(session.find_first_not_of("0123456789abcdef"), std::string::npos);
    ASSERT_EQ(r.messages().size(), 1u);
    const auto welcome = std::get<p::Welcome>(r.messages()[0]);
    EXPECT_EQ(welcome.id, p::RequestId{std::int64_t{1}});
    EXPECT_EQ(welcome.field.definition.id, "b4-64x36-s1");
    EXPECT_FALSE(r.body.contains("closed"));
    EXPECT_NE(r.headers.find("Content-Type: application/json"), std::string::npos) << r.headers;
    EXPECT_NE(r.headers.find("Cache-Control: no-store"), std::string::npos) << r.headers;
    EXPECT_EQ(r.headers.find("Access-Control"), std::string::npos) << "no CORS at all";
    EXPECT_EQ(server->api_sessions().size(), 1u);

    // seeking: no reply; aim: the target; grab: the content and its link.
    const auto replies = curl_many({{"POST", "/api/session/" + session, R"({"type":"seeking","v":1})"},
                                    {"POST", "/api/session/" + session,
                                     R"({"type":"aim","v":1,"id":2,"point":[10.5,4.25],"confidence":0.9})"},
                                    {"POST", "/api/session/" + session, R"({"type":"grab","v":1,"id":"g1","point":[10.5,4.25]})"}});
    EXPECT_EQ(replies[0].status, 200);
    EXPECT_EQ(replies[0].raw, R"({"messages":[]})");
    ASSERT_EQ(replies[1].messages().size(), 1u) << replies[1].raw;
    const auto target = std::get<p::Target>(replies[1].messages()[0]);
    EXPECT_EQ(target.id, p::RequestId{std::int64_t{2}});
    EXPECT_EQ(target.kind, p::ContentKind::file);
    EXPECT_EQ(target.title, "Report");
    ASSERT_EQ(replies[2].messages().size(), 1u) << replies[2].raw;
    const auto content = std::get<p::Content>(replies[2].messages()[0]);
    EXPECT_EQ(content.id, p::RequestId{std::string("g1")});
    ASSERT_TRUE(content.download);
    const ApiResponse download = call({"GET", *content.download, ""}, "-H 'Authorization: Bearer " + std::string(kApiToken) + "'");
    EXPECT_EQ(download.status, 200);
    EXPECT_EQ(download.raw, "the report\n");

    // A bad message is answered and keeps the session, as over the WebSocket.
    const ApiResponse bad = post("/api/session/" + session, R"({"type":"grab","v":1,"id":"g2","point":"here"})");
    EXPECT_EQ(bad.status, 200);
    ASSERT_EQ(bad.messages().size(), 1u);
    EXPECT_EQ(std::get<p::Error>(bad.messages()[0]).code, p::ErrorCode::bad_request);
    EXPECT_EQ(bad.closed(), 0);
    EXPECT_EQ(server->api_sessions().size(), 1u);
}

TEST_F(ProviderHttpApi, ARefusedHelloIsClosedWithoutASession) {
    start();
    const ApiResponse wrong = post("/api/hello", api_hello("not-the-token-0123456789abcdef"));
    EXPECT_EQ(wrong.status, 200);
    ASSERT_EQ(wrong.messages().size(), 1u) << wrong.raw;
    EXPECT_EQ(std::get<p::Error>(wrong.messages()[0]).code, p::ErrorCode::unauthorized);
    EXPECT_EQ(wrong.closed(), 1008);
    EXPECT_FALSE(wrong.body.contains("session"));

    const ApiResponse not_hello = post("/api/hello", R"({"type":"aim","v":1,"point":[1,1],"confidence":1})");
    EXPECT_EQ(not_hello.closed(), 1008);
    EXPECT_EQ(std::get<p::Error>(not_hello.messages().at(0)).code, p::ErrorCode::unauthorized);
    const ApiResponse version = post("/api/hello", R"({"type":"hello","v":2,"id":1,"token":"x","client":""})");
    EXPECT_EQ(version.closed(), 1008);
    EXPECT_EQ(std::get<p::Error>(version.messages().at(0)).code, p::ErrorCode::unsupported_version);
    EXPECT_EQ(server->api_sessions().size(), 0u);
    EXPECT_EQ(recorder->left_count(), 0u) << "no session began, so none left";
}

TEST_F(ProviderHttpApi, UnknownSessionsPathsAndMethods) {
    start();
    const std::string session = welcome();
    std::string other = session;
    other[0] = other[0] == 'a' ? 'b' : 'a';
    for (const std::string& path : {"/api/session/" + other, "/api/session/" + other + "/close",
                                    "/api/session/" + session.substr(0, 31), "/api/session/" + session + "0"}) {
        const ApiResponse r = post(path, R"({"type":"seeking","v":1})");
        EXPECT_EQ(r.status, 404) << path;
        EXPECT_EQ(r.closed(), 1008) << path;
        ASSERT_EQ(r.messages().size(), 1u) << r.raw;
        EXPECT_EQ(std::get<p::Error>(r.messages()[0]).code, p::ErrorCode::not_found);
    }
    const ApiResponse events = poll(other);
    EXPECT_EQ(events.status, 404);
    EXPECT_EQ(events.closed(), 1008);

    const ApiResponse unknown_path = post("/api/sessions", "{}");
    EXPECT_EQ(unknown_path.status, 404);
    EXPECT_EQ(unknown_path.closed(), 0) << "no session is concerned";
    EXPECT_EQ(post("/api/session/" + session + "/events", "{}").status, 405);
    const ApiResponse get_hello = call({"GET", "/api/hello", ""});
    EXPECT_EQ(get_hello.status, 405);
    EXPECT_NE(get_hello.headers.find("Allow: POST"), std::string::npos) << get_hello.headers;
    EXPECT_EQ(call({"OPTIONS", "/api/hello", ""}).status, 405) << "no CORS preflight is ever answered";
    EXPECT_EQ(call({"POST", "/index.html", "{}"}).status, 405) << "POST only under /api/";
    EXPECT_EQ(server->api_sessions().size(), 1u) << "the guesses ended nothing";
}

TEST_F(ProviderHttpApi, PostsMustBeJson) {
    start();
    for (const char* type : {"", "text/plain", "application/x-www-form-urlencoded", "multipart/form-data",
                                    "application/jsonp", "application/json-patch+json"}) {
        const ApiResponse r = call({"POST", "/api/hello", api_hello(), type});
        EXPECT_EQ(r.status, 415) << type;
        ASSERT_EQ(r.messages().size(), 1u) << r.raw;
        EXPECT_EQ(std::get<p::Error>(r.messages()[0]).code, p::ErrorCode::bad_request);
    }
    EXPECT_EQ(server->api_sessions().size(), 0u);
    EXPECT_EQ(call({"POST", "/api/hello", api_hello(), "Application/JSON; charset=utf-8"}).status, 200);
    const std::string session = welcome();
    EXPECT_EQ(call({"POST", "/api/session/" + session, R"({"type":"seeking","v":1})", "text/plain"}).status, 415);
    EXPECT_EQ(call({"POST", "/api/session/" + session + "/close", "", "text/plain"}).status, 415);
    EXPECT_EQ(server->api_sessions().size(), 2u);
}

TEST_F(ProviderHttpApi, BodiesAboveTheLimitAre413) {
    start();
    const std::string session = welcome();
    const std::string big = R"({"type":"seeking","v":1,"pad":")" + std::string(16 * 1024, 'x') + "\"}";
    const ApiResponse r = post("/api/session/" + session, big);
    EXPECT_EQ(r.status, 413);
    ASSERT_EQ(r.messages().size(), 1u) << r.raw;
    EXPECT_EQ(std::get<p::Error>(r.messages()[0]).code, p::ErrorCode::too_large);
    EXPECT_EQ(post("/api/hello", big).status, 413);
    // The session goes on.
    EXPECT_EQ(post("/api/session/" + session, R"({"type":"seeking","v":1})").status, 200);
}

TEST_F(ProviderHttpApi, RateLimitsAreTheWebSocketsOnes) {
    start();
    const std::string session = welcome();
    std::vector<Call> aims;
    for (int i = 0; i < 14; ++i)
        aims.push_back({"POST", "/api/session/" + session,
                        R"({"type":"aim","v":1,"id":)" + std::to_string(i) + R"(,"point":[1,1],"confidence":1})"});
    int limited = 0;
    for (const auto& r : curl_many(aims))
        for (const auto& m : r.messages())
            if (const auto* e = std::get_if<p::Error>(&m); e && e->code == p::ErrorCode::rate_limited) ++limited;
    EXPECT_GE(limited, 1) << "10 aims a second, in bursts of 10";
}

TEST_F(ProviderHttpApi, ALongPollIsAnsweredEmptyAtItsTimeout) {
    ApiSessionOptions options;
    options.poll_timeout = 200ms;
    start(options);
    const std::string session = welcome();
    const auto t0 = std::chrono::steady_clock::now();
    const ApiResponse r = poll(session);
    const auto took = std::chrono::steady_clock::now() - t0;
    EXPECT_EQ(r.status, 200);
    EXPECT_EQ(r.raw, R"({"messages":[]})");
    EXPECT_GE(took, 180ms);
    EXPECT_LT(took, 3s);
    EXPECT_NE(r.headers.find("Cache-Control: no-store"), std::string::npos);
    // Twice on one kept-alive connection, then a message on it too.
    const auto again = curl_many({{"GET", "/api/session/" + session + "/events", ""},
                                  {"GET", "/api/session/" + session + "/events", ""},
                                  {"POST", "/api/session/" + session, R"({"type":"aim","v":1,"point":[1,1],"confidence":1})"}});
    EXPECT_EQ(again[0].raw, R"({"messages":[]})");
    EXPECT_EQ(again[1].raw, R"({"messages":[]})");
    ASSERT_EQ(again[2].messages().size(), 1u) << again[2].raw;
    EXPECT_TRUE(std::holds_alternative<p::Target>(again[2].messages()[0]));
    EXPECT_EQ(server->api_sessions().polls_waiting(), 0u);
}

TEST_F(ProviderHttpApi, AnOpenPollHearsThatTheScreensChanged) {
    ApiSessionOptions options;
    options.poll_timeout = 10s;
    start(options);
    const std::string polled = welcome(), idle = welcome();
    auto pending = std::async(std::launch::async, [&] { return poll(polled); });
    ASSERT_TRUE(eventually([&] { return server->api_sessions().polls_waiting() == 1; }));
    const auto t0 = std::chrono::steady_clock::now();
    service->set_screens(lay_out_desktop({{"left", 0, 0, 1920, 1080}, {"right", 1920, 0, 1920, 1080}}));
    ASSERT_EQ(pending.wait_for(5s), std::future_status::ready);
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s) << "at once, not at the poll's timeout";
    const ApiResponse r = pending.get();
    EXPECT_EQ(r.status, 200);
    EXPECT_EQ(r.raw, R"({"messages":[],"closed":1012})");
    EXPECT_EQ(server->api_sessions().size(), 1u) << "the polled session ended";
    EXPECT_EQ(recorder->left_count(), 1u);

    // The other, welcomed before too, hears it at its next request.
    const ApiResponse stale = post("/api/session/" + idle, R"({"type":"aim","v":1,"point":[1,1],"confidence":1})");
    EXPECT_EQ(stale.status, 200);
    EXPECT_EQ(stale.raw, R"({"messages":[],"closed":1012})");
    EXPECT_EQ(server->api_sessions().size(), 0u);
    EXPECT_EQ(recorder->left_count(), 2u);
    EXPECT_EQ(post("/api/session/" + idle, R"({"type":"seeking","v":1})").status, 404);

    // A new session gets the new field; a poll starting on a stale session is
    // answered at once.
    const ApiResponse fresh = post("/api/hello", api_hello());
    EXPECT_EQ(std::get<p::Welcome>(fresh.messages().at(0)).field.screens.size(), 2u);
    const std::string newer = fresh.session();
    service->set_screens(lay_out_desktop({{"one", 0, 0, 1920, 1080}}));
    const auto t1 = std::chrono::steady_clock::now();
    EXPECT_EQ(poll(newer).raw, R"({"messages":[],"closed":1012})");
    EXPECT_LT(std::chrono::steady_clock::now() - t1, 2s);
}

TEST_F(ProviderHttpApi, IdleSessionsExpireAndTheListenerHearsIt) {
    ApiSessionOptions options;
    options.idle_expiry = 800ms;
    options.poll_timeout = 1200ms;
    start(options);
    const std::string idle = welcome(), busy = welcome();
    // Requests keep a session; so does an open poll longer than the expiry.
    for (int i = 0; i < 6; ++i) {
        std::this_thread::sleep_for(200ms);
        EXPECT_EQ(post("/api/session/" + busy, R"({"type":"seeking","v":1})").status, 200);
    }
    EXPECT_TRUE(eventually([&] { return server->api_sessions().size() == 1; }, 3s));
    EXPECT_EQ(recorder->left_count(), 1u);
    EXPECT_EQ(post("/api/session/" + idle, R"({"type":"seeking","v":1})").status, 404);
    EXPECT_EQ(poll(busy).raw, R"({"messages":[]})");
    EXPECT_EQ(post("/api/session/" + busy, R"({"type":"seeking","v":1})").status, 200);

    EXPECT_TRUE(eventually([&] { return server->api_sessions().size() == 0; }, 3s));
    EXPECT_EQ(recorder->left_count(), 2u);
    EXPECT_EQ(poll(busy).status, 404);
}

TEST_F(ProviderHttpApi, The257thSessionIsRefused) {
    start();
    ASSERT_EQ(ApiSessionOptions{}.max_sessions, 256u);
    std::vector<Call> hellos(256, Call{"POST", "/api/hello", api_hello()});
    std::vector<std::string> sessions;
    for (const auto& r : curl_many(hellos)) {
        EXPECT_EQ(r.status, 200);
        sessions.push_back(r.session());
    }
    EXPECT_EQ(server->api_sessions().size(), 256u);
    const ApiResponse refused = post("/api/hello", api_hello());
    EXPECT_EQ(refused.status, 503);
    EXPECT_FALSE(refused.body.contains("session"));
    EXPECT_EQ(refused.closed(), 1013);
    ASSERT_EQ(refused.messages().size(), 1u) << refused.raw;
    const auto error = std::get<p::Error>(refused.messages()[0]);
    EXPECT_EQ(error.code, p::ErrorCode::rate_limited);
    EXPECT_NE(error.message.find("256 HTTPS sessions"), std::string::npos) << error.message;
    // One ends: room again.
    EXPECT_EQ(post("/api/session/" + sessions[7] + "/close", "").closed(), 1000);
    EXPECT_EQ(post("/api/hello", api_hello()).status, 200);
}

TEST_F(ProviderHttpApi, AClientLeavingMidPollLeavesNothingBehind) {
    ApiSessionOptions options;
    options.poll_timeout = 20s;
    start(options);
    const std::string session = welcome();
    const auto t0 = std::chrono::steady_clock::now();
    const ApiResponse cut = poll(session, "--max-time 0.5");
    EXPECT_EQ(cut.status, 0) << "curl gave up";
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);
    // The connection, its timer and the waiter are gone at once, not after 20 s.
    EXPECT_TRUE(eventually([&] { return server->connection_count() == 0; }, 2s)) << server->connection_count();
    EXPECT_EQ(server->api_sessions().polls_waiting(), 0u);
    // The HTTP session itself stays until it expires: the phone may poll again.
    EXPECT_EQ(server->api_sessions().size(), 1u);
    EXPECT_EQ(post("/api/session/" + session, R"({"type":"aim","v":1,"point":[1,1],"confidence":1})").status, 200);
    EXPECT_EQ(call({"GET", "/", ""}).status, 200) << "the server serves on";
}

TEST_F(ProviderHttpApi, CloseEndsTheSessionAndAnswersItsPoll) {
    ApiSessionOptions options;
    options.poll_timeout = 10s;
    start(options);
    const std::string session = welcome();
    auto pending = std::async(std::launch::async, [&] { return poll(session); });
    ASSERT_TRUE(eventually([&] { return server->api_sessions().polls_waiting() == 1; }));
    const ApiResponse closed = post("/api/session/" + session + "/close", "");
    EXPECT_EQ(closed.status, 200);
    EXPECT_EQ(closed.raw, R"({"messages":[],"closed":1000})");
    ASSERT_EQ(pending.wait_for(5s), std::future_status::ready);
    EXPECT_EQ(pending.get().raw, R"({"messages":[],"closed":1000})");
    EXPECT_EQ(server->api_sessions().size(), 0u);
    EXPECT_EQ(recorder->left_count(), 1u);
    EXPECT_EQ(post("/api/session/" + session, R"({"type":"seeking","v":1})").status, 404);
    EXPECT_EQ(post("/api/session/" + session + "/close", "").status, 404);
}

TEST_F(ProviderHttpApi, ANewerPollTakesOverAndStopAnswersPolls) {
    ApiSessionOptions options;
    options.poll_timeout = 10s;
    start(options);
    const std::string session = welcome();
    auto first = std::async(std::launch::async, [&] { return poll(session); });
    ASSERT_TRUE(eventually([&] { return server->api_sessions().polls_waiting() == 1; }));
    auto second = std::async(std::launch::async, [&] { return poll(session); });
    ASSERT_EQ(first.wait_for(5s), std::future_status::ready);
    EXPECT_EQ(first.get().raw, R"({"messages":[]})");
    ASSERT_TRUE(eventually([&] { return server->api_sessions().polls_waiting() == 1; }));

    const auto t0 = std::chrono::steady_clock::now();
    server->stop();
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 1500ms) << "no poll held the stop for its grace period";
    ASSERT_EQ(second.wait_for(5s), std::future_status::ready);
    EXPECT_EQ(second.get().raw, R"({"messages":[],"closed":1001})");
    EXPECT_EQ(recorder->left_count(), 1u);
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
