// The provider's service half: pairing, the TLS identity, the message
// handling without sockets, and a real server on 127.0.0.1 with a Beast TLS
// WebSocket client that pins the certificate. Built only with the provider
// (UMF_PROVIDER_TESTS, see tests/CMakeLists.txt).
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>
#include <openssl/x509.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <thread>

#include "provider/common/config_dir.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/tls_websocket_client.hpp"

namespace {

using umf::test::TempDir;

namespace fs = std::filesystem;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace p = umf::protocol;
using namespace umf::provider;

constexpr auto kOpTimeout = std::chrono::seconds(5);


p::Message parse_reply(const std::string& text) {
    auto parsed = p::parse_message(text, p::kRequesterLimits);
    if (const auto* e = std::get_if<p::ProtocolError>(&parsed)) {
        ADD_FAILURE() << "reply does not parse: " << e->message << "\n" << text.substr(0, 200);
        return p::Error{};
    }
    return std::get<p::Message>(parsed);
}

std::string server_hello(const std::string& token, int id = 1) {
    return p::encode(p::Hello{p::RequestId{std::int64_t{id}}, token, "provider_server_test"});
}

// The server tests' requester (tests/support/tls_websocket_client.hpp) with
// the protocol's first steps.
class Client : public umf::test::TlsWebSocketClient {
public:
    using TlsWebSocketClient::TlsWebSocketClient;

    p::Message read_message() {
        auto [ec, text] = read();
        EXPECT_FALSE(ec) << ec.message();
        return parse_reply(text);
    }
    // The welcome for a good token.
    void connect_and_hello(const std::string& token) {
        ASSERT_FALSE(connect());
        ASSERT_FALSE(send(server_hello(token)));
        const p::Message m = read_message();
        ASSERT_TRUE(std::holds_alternative<p::Welcome>(m)) << p::type_name(m);
    }
};

// ---- pairing and identity ------------------------------------------------

TEST(ProviderPairing, Base64urlAndTokens) {
    const unsigned char bytes[] = {0xfb, 0xff, 0xbf, 0x00, 0x10};
    EXPECT_EQ(base64url(bytes, 0), "");
    EXPECT_EQ(base64url(bytes, 1), "-w");
    EXPECT_EQ(base64url(bytes, 3), "-_-_");
    EXPECT_EQ(base64url(bytes, 5), "-_-_ABA");
    const std::string a = make_token(), b = make_token();
    EXPECT_GE(a.size(), 22u);
    EXPECT_NE(a, b);
    EXPECT_TRUE(tokens_equal(a, a));
    EXPECT_FALSE(tokens_equal(a, b));
    EXPECT_FALSE(tokens_equal(a, a.substr(0, a.size() - 1)));
    EXPECT_FALSE(tokens_equal(a, ""));
}

TEST(ProviderPairing, Url) {
    EXPECT_EQ(pairing_url("192.168.1.20", 47470, "tok", "ab"), "https://192.168.1.20:47470/#t=tok&fp=ab");
    EXPECT_EQ(pairing_url("fe80::1", 443, "tok", "ab"), "https://[fe80::1]:443/#t=tok&fp=ab");
}

TEST(ProviderPairing, TokenIsKeptAndRotates) {
    TempDir dir;
    const std::string first = load_or_create_token(dir.path);
    EXPECT_EQ(load_or_create_token(dir.path), first);
    struct stat st {};
    ASSERT_EQ(stat((dir.path / kTokenFile).c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
    const std::string rotated = load_or_create_token(dir.path, true);
    EXPECT_NE(rotated, first);
    EXPECT_EQ(load_or_create_token(dir.path), rotated);
}

TEST(ProviderIdentity, CreatedOnceThenReused) {
    TempDir dir;
    const fs::path config = dir.path / "nested" / "umf";
    const TlsIdentity first = load_or_create_tls_identity(config);
    EXPECT_EQ(first.fingerprint.size(), 64u);
    EXPECT_EQ(first.fingerprint.find_first_not_of("0123456789abcdef"), std::string::npos);
    // The pin is the root's, served after the serving certificate.
    EXPECT_NE(certificate_fingerprint(first.certificate_pem), first.fingerprint);
    EXPECT_EQ(certificate_fingerprint(*read_small_file(config / kRootCertificateFile)), first.fingerprint);
    for (const char* name : {kRootCertificateFile, kRootKeyFile, kServingCertificateFile, kServingKeyFile}) {
        struct stat st {};
        ASSERT_EQ(stat((config / name).c_str(), &st), 0);
        EXPECT_EQ(st.st_mode & 0777, 0600u) << name;
    }
    const TlsIdentity again = load_or_create_tls_identity(config);
    EXPECT_EQ(again.fingerprint, first.fingerprint);
    EXPECT_EQ(again.private_key_pem, first.private_key_pem);
    EXPECT_NE(create_tls_identity().fingerprint, first.fingerprint);

    // Half a root is refused rather than silently replaced.
    fs::remove(config / kRootKeyFile);
    EXPECT_THROW(load_or_create_tls_identity(config), TlsIdentityError);
}

// ---- the service without sockets ------------------------------------------

class ProviderService : public ::testing::Test {
protected:
    Service service{default_service_config(), "good-token-0123456789abcdef"};
    SessionState state;
    void welcome() {
        auto out = service.handle_text(state, server_hello("good-token-0123456789abcdef"));
        ASSERT_EQ(out.replies.size(), 1u);
        ASSERT_TRUE(std::holds_alternative<p::Welcome>(out.replies[0]));
        ASSERT_FALSE(out.close);
        ASSERT_TRUE(state.welcomed);
    }
    static p::ErrorCode code_of(const Replies& out) {
        EXPECT_EQ(out.replies.size(), 1u);
        const auto* e = out.replies.empty() ? nullptr : std::get_if<p::Error>(&out.replies[0]);
        EXPECT_NE(e, nullptr);
        return e ? e->code : p::ErrorCode::internal;
    }
};

TEST_F(ProviderService, WelcomeCarriesTheDefaultFieldAndBalancedPreset) {
    auto out = service.handle_text(state, server_hello("good-token-0123456789abcdef", 42));
    ASSERT_EQ(out.replies.size(), 1u);
    const auto& w = std::get<p::Welcome>(out.replies[0]);
    EXPECT_EQ(w.id, p::RequestId{std::int64_t{42}});
    EXPECT_EQ(w.field.definition.id, "b4-64x36-s1");
    ASSERT_EQ(w.field.screens.size(), 1u);
    EXPECT_EQ(w.field.screens[0].region, (p::FieldRect{0, 0, 64, 36}));
    EXPECT_EQ(w.field.screens[0].width_px, 1920);
    EXPECT_EQ(w.overlay.preset, "balanced");
    EXPECT_EQ(w.limits.max_message_bytes, 16384);
    EXPECT_FALSE(w.provider.name.empty());
    // What the provider sends parses on the requester's side.
    EXPECT_EQ(parse_reply(p::encode(out.replies[0])), out.replies[0]);
}

TEST_F(ProviderService, ScreensThatChangeMoveTheFieldAndRestartOlderSessions) {
    welcome();
    const auto before = service.screens();
    EXPECT_EQ(before->generation, 0u);
    // A second screen arrives: the 4K-wide desktop needs the larger field.
    service.set_screens(lay_out_desktop({{"left", 0, 0, 1920, 1080}, {"right", 1920, 0, 1920, 1080}}));
    const auto after = service.screens();
    EXPECT_EQ(after->generation, 1u);
    EXPECT_EQ(after->field.screens.size(), 2u);
    EXPECT_NE(after->field.definition.id, before->field.definition.id);
    // The snapshot taken before stays whole for whoever holds it.
    EXPECT_EQ(before->field.screens.size(), 1u);

    // The session welcomed before is told to connect again, without a reply.
    auto stale = service.handle_text(state, R"({"type":"aim","v":1,"id":3,"point":[1,2],"confidence":0.5})");
    EXPECT_TRUE(stale.replies.empty());
    EXPECT_TRUE(stale.close);
    EXPECT_TRUE(stale.restart);

    // A new session gets the new field and is served.
    SessionState fresh;
    auto out = service.handle_text(fresh, server_hello("good-token-0123456789abcdef"));
    ASSERT_EQ(out.replies.size(), 1u);
    EXPECT_EQ(std::get<p::Welcome>(out.replies[0]).field.screens.size(), 2u);
    auto aim = service.handle_text(fresh, R"({"type":"aim","v":1,"id":4,"point":[100,30],"confidence":0.9})");
    ASSERT_EQ(aim.replies.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<p::Target>(aim.replies[0]));
    EXPECT_FALSE(aim.close);
    const auto point = service.screen_point({100, 30});
    ASSERT_TRUE(point);
    EXPECT_EQ(point->screen, 1);
    EXPECT_GE(point->root_x, 1920);

    EXPECT_THROW(service.set_screens(DesktopLayout{}), std::invalid_argument);
    EXPECT_EQ(service.screens()->generation, 1u);
}

TEST_F(ProviderService, BeforeWelcomeEverythingElseCloses) {
    auto wrong = service.handle_text(state, server_hello("wrong-token-0123456789abcdef"));
    EXPECT_EQ(code_of(wrong), p::ErrorCode::unauthorized);
    EXPECT_TRUE(wrong.close);
    EXPECT_FALSE(state.welcomed);

    auto aim = service.handle_text(state, R"({"type":"aim","v":1,"id":3,"point":[1,2],"confidence":0.5})");
    EXPECT_EQ(code_of(aim), p::ErrorCode::unauthorized);
    EXPECT_TRUE(aim.close);

    auto malformed = service.handle_text(state, "{not json");
    EXPECT_EQ(code_of(malformed), p::ErrorCode::bad_request);
    EXPECT_TRUE(malformed.close);

    auto version = service.handle_text(state, R"({"type":"hello","v":2,"id":1,"token":"x","client":""})");
    EXPECT_EQ(code_of(version), p::ErrorCode::unsupported_version);
    EXPECT_TRUE(version.close);

    auto binary = service.handle_binary(state);
    EXPECT_EQ(code_of(binary), p::ErrorCode::bad_request);
    EXPECT_TRUE(binary.close);
    EXPECT_FALSE(state.welcomed);
}

TEST_F(ProviderService, AfterWelcomeRequestsAreAnsweredAndNothingCloses) {
    welcome();
    EXPECT_TRUE(service.handle_text(state, R"({"type":"seeking","v":1})").replies.empty());

    auto aim = service.handle_text(state, R"({"type":"aim","v":1,"id":3,"point":[31.5,17.25],"confidence":0.9})");
    ASSERT_EQ(aim.replies.size(), 1u);
    EXPECT_EQ(std::get<p::Target>(aim.replies[0]),
              (p::Target{p::RequestId{std::int64_t{3}}, {31.5, 17.25}, p::ContentKind::none, ""}));

    auto grab = service.handle_text(state, R"({"type":"grab","v":1,"id":"g1","point":[1,1]})");
    ASSERT_EQ(grab.replies.size(), 1u);
    const auto& content = std::get<p::Content>(grab.replies[0]);
    EXPECT_EQ(content.id, p::RequestId{std::string("g1")});
    EXPECT_EQ(content.kind, p::ContentKind::none);

    for (const char* bad : {"{not json", R"({"type":"teleport","v":1})", R"({"type":"grab","v":1,"id":"g2","point":"here"})",
                            R"({"type":"target","v":1,"point":[1,1],"kind":"none","title":""})"}) {
        auto out = service.handle_text(state, bad);
        EXPECT_EQ(code_of(out), p::ErrorCode::bad_request) << bad;
        EXPECT_FALSE(out.close) << bad;
    }
    auto id_kept = service.handle_text(state, R"({"type":"grab","v":1,"id":"g2","point":"here"})");
    EXPECT_EQ(std::get<p::Error>(id_kept.replies[0]).id, p::RequestId{std::string("g2")});
    auto again = service.handle_text(state, server_hello("good-token-0123456789abcdef"));
    EXPECT_EQ(code_of(again), p::ErrorCode::bad_request);
    EXPECT_FALSE(again.close);
    EXPECT_EQ(code_of(service.handle_binary(state)), p::ErrorCode::bad_request);
    EXPECT_EQ(code_of(service.handle_text(state, std::string(20000, ' '))), p::ErrorCode::too_large);
    EXPECT_TRUE(state.welcomed);
}

TEST_F(ProviderService, TokenCanBeReplaced) {
    service.set_token("new-token-0123456789abcdefgh");
    auto old = service.handle_text(state, server_hello("good-token-0123456789abcdef"));
    EXPECT_EQ(code_of(old), p::ErrorCode::unauthorized);
    SessionState fresh;
    service.handle_text(fresh, server_hello("new-token-0123456789abcdefgh"));
    EXPECT_TRUE(fresh.welcomed);
}

// ---- a real server ------------------------------------------------------------

class ProviderServer : public ::testing::Test {
protected:
    void SetUp() override {
        identity = load_or_create_tls_identity(dir.path);
        token = load_or_create_token(dir.path);
        start();
    }
    void start() {
        service = std::make_shared<Service>(default_service_config(), token);
        server = make_server(service, identity);
        server->start();
        ASSERT_NE(server->port(), 0);
    }
    std::unique_ptr<Client> client() { return std::make_unique<Client>(server->port(), identity.fingerprint); }

    TempDir dir;
    TlsIdentity identity;
    std::string token;
    std::shared_ptr<Service> service;
    std::unique_ptr<Server> server;
};

TEST_F(ProviderServer, HelloWithTheTokenIsWelcomed) {
    auto c = client();
    ASSERT_FALSE(c->connect());
    ASSERT_FALSE(c->send(server_hello(token, 1)));
    const p::Message m = c->read_message();
    const auto* w = std::get_if<p::Welcome>(&m);
    ASSERT_NE(w, nullptr) << p::type_name(m);
    EXPECT_EQ(w->id, p::RequestId{std::int64_t{1}});
    EXPECT_EQ(w->field.definition.id, "b4-64x36-s1");
    EXPECT_EQ(w->overlay.preset, "balanced");
}

TEST_F(ProviderServer, WrongTokenIsUnauthorizedThenClosed) {
    auto c = client();
    ASSERT_FALSE(c->connect());
    ASSERT_FALSE(c->send(server_hello("not-the-token-0123456789abc")));
    const p::Message m = c->read_message();
    ASSERT_TRUE(std::holds_alternative<p::Error>(m));
    EXPECT_EQ(std::get<p::Error>(m).code, p::ErrorCode::unauthorized);
    EXPECT_EQ(c->read_close(), websocket::close_code::policy_error);
}

TEST_F(ProviderServer, AnAddressGuessingTokensIsStopped) {
    for (int i = 0; i < kMaxWrongTokens; ++i) {
        auto c = client();
        ASSERT_FALSE(c->connect());
        ASSERT_FALSE(c->send(server_hello("guess-" + std::to_string(i) + "-0123456789abcdefgh")));
        EXPECT_EQ(std::get<p::Error>(c->read_message()).code, p::ErrorCode::unauthorized);
    }
    auto c = client();
    ASSERT_FALSE(c->connect());
    ASSERT_FALSE(c->send(server_hello(token)));
    const p::Message m = c->read_message();
    ASSERT_TRUE(std::holds_alternative<p::Error>(m)) << p::type_name(m);
    EXPECT_EQ(std::get<p::Error>(m).code, p::ErrorCode::rate_limited) << "even the right token, for a minute";
    EXPECT_EQ(c->read_close(), websocket::close_code::policy_error);
}

TEST_F(ProviderServer, ConnectionsBeyondTheCapAreClosed) {
    server->stop();
    ServerOptions options;
    options.max_connections = 2;
    server = make_server(std::make_shared<const Service>(default_service_config(), token), identity, options);
    server->start();
    auto a = client(), b = client(), c = client();
    a->connect_and_hello(token);
    b->connect_and_hello(token);
    EXPECT_TRUE(c->connect()) << "a third connection is refused";
    a.reset();
    for (int i = 0; i < 100 && server->connection_count() > 1; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    auto d = client();
    d->connect_and_hello(token);  // room again
}

TEST_F(ProviderServer, ServesAWelcomedSession) {
    auto c = client();
    c->connect_and_hello(token);

    auto expect_error = [&](const std::string& text, bool binary, p::ErrorCode code) {
        ASSERT_FALSE(c->send(text, binary));
        const p::Message m = c->read_message();
        ASSERT_TRUE(std::holds_alternative<p::Error>(m)) << p::type_name(m);
        EXPECT_EQ(std::get<p::Error>(m).code, code) << text;
    };
    expect_error("{\"type\":", false, p::ErrorCode::bad_request);
    expect_error(std::string("\x00\xff\x13garbage", 10), true, p::ErrorCode::bad_request);
    expect_error(R"({"type":"teleport","v":1})", false, p::ErrorCode::bad_request);

    // seeking gets no reply: the next message is the aim's target.
    ASSERT_FALSE(c->send(R"({"type":"seeking","v":1})"));
    ASSERT_FALSE(c->send(R"({"type":"aim","v":1,"id":2,"point":[10.5,4.25],"confidence":0.8})"));
    const p::Message t = c->read_message();
    ASSERT_TRUE(std::holds_alternative<p::Target>(t)) << p::type_name(t);
    EXPECT_EQ(std::get<p::Target>(t).id, p::RequestId{std::int64_t{2}});
    EXPECT_EQ(std::get<p::Target>(t).point, (p::FieldPoint{10.5, 4.25}));
    EXPECT_EQ(std::get<p::Target>(t).kind, p::ContentKind::none);

    ASSERT_FALSE(c->send(R"({"type":"grab","v":1,"id":7,"point":[10.5,4.25]})"));
    const p::Message g = c->read_message();
    ASSERT_TRUE(std::holds_alternative<p::Content>(g)) << p::type_name(g);
    EXPECT_EQ(std::get<p::Content>(g).id, p::RequestId{std::int64_t{7}});
    EXPECT_EQ(std::get<p::Content>(g).kind, p::ContentKind::none);
}

TEST_F(ProviderServer, OversizedMessageClosesWithTooBigAndTheServerGoesOn) {
    auto c = client();
    c->connect_and_hello(token);
    ASSERT_FALSE(c->send(std::string(p::kMaxRequestBytes + 1, ' ')));
    EXPECT_EQ(c->read_close(), websocket::close_code::too_big);

    auto next = client();
    next->connect_and_hello(token);
}

// Sent whole, an oversized message still gets its 1009: the provider reads
// and drops the rest instead of closing under it, which would reset the
// connection and could destroy the close before the client reads it.
TEST_F(ProviderServer, AnOversizedMessageSentWholeStillSeesItsClose) {
    for (int attempt = 0; attempt < 5; ++attempt) {
        auto c = client();
        c->connect_and_hello(token);
        c->send(std::string(4 << 20, ' '));  // its result depends on how much was read
        EXPECT_EQ(c->read_close(), websocket::close_code::too_big) << "attempt " << attempt;
    }
}

TEST_F(ProviderServer, TwoClientsAtOnce) {
    auto a = client(), b = client();
    a->connect_and_hello(token);
    b->connect_and_hello(token);
    ASSERT_FALSE(a->send(R"({"type":"aim","v":1,"id":"a","point":[1,1],"confidence":1})"));
    ASSERT_FALSE(b->send(R"({"type":"aim","v":1,"id":"b","point":[2,2],"confidence":1})"));
    EXPECT_EQ(std::get<p::Target>(b->read_message()).id, p::RequestId{std::string("b")});
    EXPECT_EQ(std::get<p::Target>(a->read_message()).id, p::RequestId{std::string("a")});
}

TEST_F(ProviderServer, ShutdownClosesSessionsWithGoingAway) {
    auto a = client(), b = client();
    a->connect_and_hello(token);
    b->connect_and_hello(token);
    auto stopped = std::async(std::launch::async, [this] { server->stop(); });
    EXPECT_EQ(a->read_close(), websocket::close_code::going_away);
    EXPECT_EQ(b->read_close(), websocket::close_code::going_away);
    ASSERT_EQ(stopped.wait_for(kOpTimeout), std::future_status::ready);
    EXPECT_EQ(server->connection_count(), 0u);

    // A restart keeps the identity, so the pinned fingerprint still holds.
    server.reset();
    EXPECT_EQ(load_or_create_tls_identity(dir.path).fingerprint, identity.fingerprint);
    start();
    auto c = client();
    c->connect_and_hello(token);
}

TEST_F(ProviderServer, ASessionFromBeforeTheScreensChangedIsRestarted) {
    auto old = client();
    old->connect_and_hello(token);
    service->set_screens(lay_out_desktop({{"left", 0, 0, 1920, 1080}, {"right", 1920, 0, 1920, 1080}}));
    ASSERT_FALSE(old->send(R"({"type":"aim","v":1,"id":2,"point":[10,10],"confidence":0.9})"));
    EXPECT_EQ(old->read_close(), websocket::close_code::service_restart);
    // Connecting again gives the new field.
    auto again = client();
    ASSERT_FALSE(again->connect());
    ASSERT_FALSE(again->send(server_hello(token)));
    const p::Message m = again->read_message();
    ASSERT_TRUE(std::holds_alternative<p::Welcome>(m));
    EXPECT_EQ(std::get<p::Welcome>(m).field.screens.size(), 2u);
}

TEST_F(ProviderServer, PinningRefusesAnotherCertificate) {
    Client c(server->port(), create_tls_identity().fingerprint);
    EXPECT_TRUE(c.connect());
}

TEST_F(ProviderServer, HttpsServesThePageAndNothingElse) {
    auto c = client();
    auto [ec, status] = c->http_get("/");
    EXPECT_FALSE(ec) << ec.message();
    EXPECT_EQ(status, 200u);
    auto unknown = client();
    EXPECT_EQ(unknown->http_get("/provider-key.pem").second, 404u);
    auto other = client();
    EXPECT_TRUE(other->connect("/elsewhere"));  // an upgrade on another path is refused too
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
