// Puts against a real server on 127.0.0.1 (docs/PROTOCOL.md, "Put" and
// "Upload"): a TLS WebSocket requester puts, a scripted decider answers for
// the person at the screen, curl (an independent client) or a raw TLS client
// uploads, a fake xdg-open records what the desktop was asked to open, and
// the put folder is checked for exactly what should be there, hidden
// temporary files included.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/time.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cctype>
#include <future>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>

#include "native/sha256.hpp"
#include "provider/content/file_facts.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/http_error_body.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/provider/put_test_support.hpp"
#include "tests/support/pinned_client.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/tls_websocket_client.hpp"

namespace {

namespace fs = std::filesystem;
namespace net = boost::asio;
namespace ssl = boost::asio::ssl;
namespace beast = boost::beast;
namespace http = beast::http;
namespace p = umf::protocol;
using namespace umf::provider;
using umf::test::FakeXdgOpen;
using umf::test::folder_names;
using umf::test::run_command;
using umf::test::ScriptedDecider;
using umf::test::TempDir;
using umf::test::file_put;

constexpr const char* kPutServerToken = "put-server-token-0123456789ab";

// The server tests' requester (tests/support/tls_websocket_client.hpp)
// speaking the protocol's messages.
class Requester : public umf::test::TlsWebSocketClient {
public:
    using TlsWebSocketClient::TlsWebSocketClient;
    using TlsWebSocketClient::send;

    beast::error_code send(const p::Message& m) { return send(p::encode(m)); }
    p::Message read() {
        auto [ec, text] = TlsWebSocketClient::read();
        EXPECT_FALSE(ec) << ec.message();
        if (ec) return p::Error{std::nullopt, p::ErrorCode::internal, "read failed: " + ec.message()};
        auto parsed = p::parse_message(text, p::kRequesterLimits);
        if (const auto* e = std::get_if<p::ProtocolError>(&parsed)) {
            ADD_FAILURE() << "does not parse: " << e->message;
            return p::Error{};
        }
        return std::get<p::Message>(parsed);
    }
    // Hello (with a device when given); the welcome.
    p::Welcome hello(const std::optional<std::string>& device = std::nullopt, const std::string& token = kPutServerToken) {
        EXPECT_FALSE(connect());
        EXPECT_FALSE(send(p::Hello{p::RequestId{std::int64_t{1}}, token, "put_server_test", device}));
        const p::Message m = read();
        const auto* w = std::get_if<p::Welcome>(&m);
        EXPECT_NE(w, nullptr) << p::type_name(m);
        return w ? *w : p::Welcome{};
    }
};

// Raw HTTP over TLS, blocking with a receive timeout: for what curl will not
// send (half a body, then gone; a wrong Content-Length).
class RawTls {
public:
    RawTls(unsigned short port, const std::string& fingerprint)
        : tls_(umf::test::pinned_client_context(fingerprint)), stream_(io_, tls_) {
        beast::get_lowest_layer(stream_).connect(net::ip::tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
        timeval tv{5, 0};
        ::setsockopt(beast::get_lowest_layer(stream_).native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
        stream_.handshake(ssl::stream_base::client);
    }
    void write(const std::string& bytes) { net::write(stream_, net::buffer(bytes)); }
    // The answer's status, 0 when none came.
    int read_status(std::string* body = nullptr) {
        beast::flat_buffer buffer;
        http::response<http::string_body> res;
        beast::error_code ec;
        http::read(stream_, buffer, res, ec);
        if (ec) return 0;
        if (body) *body = res.body();
        return static_cast<int>(res.result_int());
    }
    // Gone without a word: no TLS close, no FIN before the bytes promised.
    void drop() { beast::get_lowest_layer(stream_).close(); }

private:
    net::io_context io_;
    ssl::context tls_;
    ssl::stream<net::ip::tcp::socket> stream_;
};

std::string random_bytes(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::string s(n, '\0');
    for (auto& c : s) c = static_cast<char>(rng());
    return s;
}

struct PutResponse {
    int status = 0;
    std::string body;
    std::string headers;  // curl_upload's
};

class PutServer : public ::testing::Test {
protected:
    TempDir dir;
    fs::path folder = dir.path / "Downloads";
    FakeXdgOpen xdg{dir.path / "bin"};
    std::shared_ptr<ScriptedDecider> decider = std::make_shared<ScriptedDecider>();
    TlsIdentity identity;
    std::shared_ptr<Service> service;
    std::unique_ptr<Server> server;
    std::chrono::milliseconds upload_ttl{60'000};

    static void SetUpTestSuite() {
        if (run_command("curl --version >/dev/null 2>&1").exit_code != 0) GTEST_SKIP() << "curl is not installed";
    }
    void SetUp() override {
        identity = load_or_create_tls_identity(dir.path / "cfg");
        start();
    }
    void start(std::chrono::milliseconds timeout = std::chrono::seconds(30),
               std::int64_t max_bytes = std::int64_t{4} << 30) {
        server.reset();
        ServiceConfig config = default_service_config();
        config.put_decider = decider;
        config.puts.folder = folder;
        config.puts.answer_timeout = timeout;
        config.puts.max_bytes = max_bytes;
        config.puts.upload_ttl = upload_ttl;
        config.puts.trusted_devices = dir.path / "cfg" / "trusted-devices.json";
        service = std::make_shared<Service>(std::move(config), kPutServerToken);
        server = make_server(service, identity);
        server->start();
    }
    std::unique_ptr<Requester> requester(const std::optional<std::string>& device = std::nullopt) {
        auto r = std::make_unique<Requester>(server->port(), identity.fingerprint);
        const p::Welcome w = r->hello(device);
        EXPECT_EQ(w.features, (std::vector<std::string>{"put", "put-hash-after"}));
        return r;
    }
    // Puts a file, has it accepted; the upload path. `hash_after`: the put
    // leaves its sha256 out, for the upload to name.
    std::string accepted_upload(Requester& r, const std::string& bytes, const std::string& id,
                                PutAnswer answer = PutAnswer::save, const std::string& name = "report.pdf",
                                bool hash_after = false) {
        const std::size_t asked = decider->offers(0).size();
        p::Put put = file_put(bytes, id, name);
        if (hash_after) put.sha256.reset();
        EXPECT_FALSE(r.send(put));
        const p::Message asking = r.read();
        EXPECT_TRUE(std::holds_alternative<p::PutStatus>(asking)) << p::type_name(asking);
        const auto offers = decider->offers(asked + 1);
        EXPECT_EQ(offers.size(), asked + 1);
        if (offers.size() <= asked) return "";
        decider->answer(offers.back().id, {answer, false});
        const p::Message m = r.read();
        const auto* s = std::get_if<p::PutStatus>(&m);
        EXPECT_TRUE(s && s->status == p::PutState::upload && s->upload) << p::type_name(m);
        EXPECT_TRUE(s && s->id == p::RequestId{id});
        return s && s->upload ? *s->upload : "";
    }
    // `options`: more of curl's ("-H 'Expect: 100-continue'", or "-H 'Expect:'" for none).
    PutResponse curl_upload(const std::string& path, const std::string& bytes, const std::string& options = "") {
        const fs::path source = dir.path / "upload.bin", body = dir.path / "answer.json",
                       headers = dir.path / "answer.headers";
        std::ofstream(source, std::ios::binary) << bytes;
        fs::remove(body);
        const auto r = run_command("curl -s -k --max-time 20 " + options + " -T '" + source.string() + "' -o '" +
                                   body.string() + "' -D '" + headers.string() + "' -w '%{http_code}' 'https://127.0.0.1:" +
                                   std::to_string(server->port()) + path + "'");
        return {std::atoi(r.out.c_str()), umf::test::file_text(body), umf::test::file_text(headers)};
    }
    std::string request_head(const std::string& path, std::size_t length, std::optional<std::size_t> offset = {},
                             const std::string& more_headers = {}) {
        return "PUT " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/octet-stream\r\n" +
               (offset ? "Upload-Offset: " + std::to_string(*offset) + "\r\n" : std::string()) + more_headers +
               "Content-Length: " + std::to_string(length) + "\r\n\r\n";
    }
    // HEAD: the Upload-Offset the provider holds; -1 without one.
    long held(const std::string& path) {
        const auto r = run_command("curl -s -k -I --max-time 10 'https://127.0.0.1:" + std::to_string(server->port()) +
                                   path + "' | tr -d '\\r' | sed -n 's/^[Uu]pload-[Oo]ffset: //p'");
        return r.out.empty() ? -1 : std::atol(r.out.c_str());
    }
    // Sends the first `n` bytes and drops the connection; the bytes the
    // provider holds once it has seen the connection end.
    long cut_after(const std::string& path, const std::string& bytes, std::size_t n) {
        {
            RawTls raw(server->port(), identity.fingerprint);
            raw.write(request_head(path, bytes.size()) + bytes.substr(0, n));
            std::this_thread::sleep_for(std::chrono::milliseconds(200));
            raw.drop();
        }
        long now = held(path), before = -2;
        for (int i = 0; i < 50 && now != before; ++i) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            before = now;
            now = held(path);
        }
        return now;
    }
};

p::ErrorCode code_of(const p::Message& m) {
    const auto* e = std::get_if<p::Error>(&m);
    EXPECT_NE(e, nullptr) << p::type_name(m);
    return e ? e->code : p::ErrorCode::internal;
}

TEST_F(PutServer, AnAcceptedUrlOpensInTheBrowser) {
    auto r = requester();
    p::Put put;
    put.id = p::RequestId{std::string("p1")};
    put.point = {31.5, 17.1};
    put.kind = p::ContentKind::url;
    put.url = "https://example.org/talk?a=1&b=2";
    ASSERT_FALSE(r->send(put));
    EXPECT_EQ(std::get<p::PutStatus>(r->read()).status, p::PutState::asking);
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, false});
    const p::Message done = r->read();
    const auto& s = std::get<p::PutStatus>(done);
    EXPECT_EQ(s.status, p::PutState::done);
    EXPECT_EQ(s.outcome, p::PutOutcome::opened);
    EXPECT_EQ(s.id, p::RequestId{std::string("p1")});
    EXPECT_EQ(xdg.opened(), std::vector<std::string>{"https://example.org/talk?a=1&b=2"});
}

TEST_F(PutServer, AnAcceptedFileIsUploadedAndSavedAndNeverOverwrites) {
    auto r = requester();
    const std::string bytes = random_bytes(3 * 1024 * 1024 + 17, 1);  // above every 16 KiB and 1 MiB limit
    const std::string path = accepted_upload(*r, bytes, "p2");
    const PutResponse answer = curl_upload(path, bytes);
    EXPECT_EQ(answer.status, 200) << answer.body;
    const auto json = nlohmann::json::parse(answer.body, nullptr, false);
    EXPECT_EQ(json.value("type", ""), "put_status");
    EXPECT_EQ(json.value("outcome", ""), "saved");
    EXPECT_EQ(json.value("name", ""), "report.pdf");
    const p::Message pushed = r->read();
    const auto& s = std::get<p::PutStatus>(pushed);
    EXPECT_EQ(s.status, p::PutState::done);
    EXPECT_EQ(s.outcome, p::PutOutcome::saved);
    EXPECT_EQ(s.name, "report.pdf");
    EXPECT_EQ(folder_names(folder), std::vector<std::string>{"report.pdf"});
    EXPECT_TRUE(umf::test::file_text(folder / "report.pdf") == bytes);

    // The same name again: stored beside it, the first untouched.
    const std::string other = random_bytes(1000, 2);
    const PutResponse second = curl_upload(accepted_upload(*r, other, "p3"), other);
    EXPECT_EQ(second.status, 200);
    EXPECT_EQ(std::get<p::PutStatus>(r->read()).name, "report (1).pdf");
    EXPECT_EQ(folder_names(folder), (std::vector<std::string>{"report (1).pdf", "report.pdf"}));
    EXPECT_TRUE(umf::test::file_text(folder / "report.pdf") == bytes);
    EXPECT_EQ(umf::test::file_text(folder / "report (1).pdf"), other);
    // The link was used.
    EXPECT_EQ(curl_upload(path, bytes).status, 404);
    EXPECT_TRUE(xdg.opened(1, std::chrono::milliseconds(100)).empty()) << "save opens nothing";
}

// A large body is read past the TLS stream when the client waited for
// "100 Continue", through the stream when it sent the body with the header:
// either way every byte arrives and the answer comes.
TEST_F(PutServer, ALargeBodyArrivesWithAndWithoutWaitingFor100Continue) {
    auto r = requester();
    int n = 0;
    for (const std::string options : {"-H 'Expect: 100-continue' --expect100-timeout 20", "-H 'Expect:'"}) {
        const std::string bytes = random_bytes(5 * 1024 * 1024 + 3, 10 + n);
        const std::string name = "big-" + std::to_string(n) + ".bin";
        const PutResponse answer =
            curl_upload(accepted_upload(*r, bytes, "q" + std::to_string(n), PutAnswer::save, name), bytes, options);
        EXPECT_EQ(answer.status, 200) << options << ": " << answer.body;
        EXPECT_EQ(std::get<p::PutStatus>(r->read()).name, name) << options;
        EXPECT_TRUE(umf::test::file_text(folder / name) == bytes) << options;
        // Read past the stream, the connection cannot go on after the answer.
        EXPECT_EQ(answer.headers.find("Connection: close") != std::string::npos, n == 0) << answer.headers;
        ++n;
    }
}

TEST_F(PutServer, AnOpenAnswerSavesThenOpensTheFile) {
    auto r = requester();
    const std::string bytes = "a small file\n";
    const PutResponse answer = curl_upload(accepted_upload(*r, bytes, "p4", PutAnswer::open, "notes.txt"), bytes);
    EXPECT_EQ(answer.status, 200);
    const p::PutStatus s = std::get<p::PutStatus>(r->read());
    EXPECT_EQ(s.outcome, p::PutOutcome::opened);
    EXPECT_EQ(s.name, "notes.txt");
    EXPECT_EQ(xdg.opened(), std::vector<std::string>{(folder / "notes.txt").string()});
}

TEST_F(PutServer, ADismissIsRefusedAndNothingLands) {
    auto r = requester();
    ASSERT_FALSE(r->send(file_put("bytes", "p5")));
    r->read();  // asking
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::dismiss, false});
    const p::Message m = r->read();
    EXPECT_EQ(code_of(m), p::ErrorCode::refused);
    EXPECT_EQ(std::get<p::Error>(m).id, p::RequestId{std::string("p5")});
    EXPECT_TRUE(folder_names(folder).empty());
}

TEST_F(PutServer, NoAnswerInTimeIsRefusedAndTheOfferWithdrawn) {
    start(std::chrono::milliseconds(200));
    auto r = requester();
    ASSERT_FALSE(r->send(file_put("bytes", "p6")));
    r->read();  // asking
    const p::Message m = r->read();
    EXPECT_EQ(code_of(m), p::ErrorCode::refused);
    EXPECT_TRUE(decider->withdrawn(decider->offers(1).at(0).id));
}

TEST_F(PutServer, AFileAboveTheLimitIsTooLargeBeforeAnyoneIsAsked) {
    start(std::chrono::seconds(30), 1024);
    auto r = requester();
    ASSERT_FALSE(r->send(file_put(std::string(1025, 'x'), "p7")));
    EXPECT_EQ(code_of(r->read()), p::ErrorCode::too_large);
    EXPECT_TRUE(decider->offers(0).empty());
}

TEST_F(PutServer, BytesThatDoNotMatchAreInterruptedAndNothingIsLeft) {
    auto r = requester();
    const std::string promised = random_bytes(100'000, 3);
    std::string sent = promised;
    sent[50'000] ^= 1;
    const PutResponse answer = curl_upload(accepted_upload(*r, promised, "p8"), sent);
    EXPECT_EQ(answer.status, 400);
    // The same error body as every other HTTP error (a 404 below).
    const auto error = p::parse_error_body(answer.body);
    ASSERT_TRUE(error) << answer.body;
    EXPECT_EQ(error->code, p::ErrorCode::interrupted);
    const p::Message m = r->read();
    EXPECT_EQ(code_of(m), p::ErrorCode::interrupted);
    EXPECT_EQ(std::get<p::Error>(m).id, p::RequestId{std::string("p8")});
    EXPECT_TRUE(folder_names(folder).empty()) << "no file, no hidden temporary file";
}

// A connection cut half way leaves the bytes that arrived with the link:
// HEAD says how many, a PUT from another offset is refused (409) and leaves
// the link, and the rest from there completes the put.
TEST_F(PutServer, AnUploadCutHalfWayResumesFromWhatArrived) {
    auto r = requester();
    std::string bytes(400000, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 31 + (i >> 9));
    const std::string path = accepted_upload(*r, bytes, "p9");
    const long have = cut_after(path, bytes, bytes.size() / 2);
    ASSERT_GT(have, 0) << "the provider kept nothing of the first half";
    ASSERT_LE(have, static_cast<long>(bytes.size() / 2));
    EXPECT_EQ(folder_names(folder).size(), 1u) << "the bytes so far wait in the temporary file";
    {
        RawTls raw(server->port(), identity.fingerprint);
        // The header alone: the provider answers it and closes without
        // reading a body it has no use for.
        raw.write(request_head(path, bytes.size() - have - 1, have + 1));
        EXPECT_EQ(raw.read_status(), 409);
    }
    EXPECT_EQ(held(path), have) << "a wrong offset leaves the link as it was";
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(path, bytes.size() - have, have) + bytes.substr(have));
        EXPECT_EQ(raw.read_status(), 200);
    }
    const p::Message m = r->read();
    const auto* done = std::get_if<p::PutStatus>(&m);
    ASSERT_NE(done, nullptr) << p::type_name(m);
    EXPECT_EQ(done->status, p::PutState::done);
    EXPECT_EQ(folder_names(folder), std::vector<std::string>{"report.pdf"});
    EXPECT_TRUE(umf::test::file_text(folder / "report.pdf") == bytes) << "the parts are not the file";
    EXPECT_EQ(held(path), -1) << "a stored upload ends the link";
}

std::string sha256_of(const std::string& bytes) {
    umf::native::Sha256 sha;
    sha.update(bytes.data(), bytes.size());
    return sha.hex();
}

// A resumed request may say the SHA-256 of the bytes it expects the
// provider to hold: the right one (in capitals, too) goes on; a request
// whose file changed under the bytes already sent ends the put at once
// (412, the reason, nothing kept) rather than after the rest.
TEST_F(PutServer, AResumeWhoseFileChangedUnderTheBytesHeldEndsThePutAtOnce) {
    auto r = requester();
    std::string bytes(300000, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 + (i >> 11));
    const std::string path = accepted_upload(*r, bytes, "p12");
    const long have = cut_after(path, bytes, bytes.size() / 2);
    ASSERT_GT(have, 0);
    const auto prefix = [&](std::string digest) {
        return "Upload-Prefix-SHA256: " + digest + "\r\n";
    };
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(path, bytes.size() - have, have, prefix("12345")));
        EXPECT_EQ(raw.read_status(), 400) << "not a SHA-256";
    }
    EXPECT_EQ(code_of(r->read()), p::ErrorCode::bad_request);
    EXPECT_EQ(held(path), -1) << "a malformed request ends the put";

    const std::string third = accepted_upload(*r, bytes, "p14");
    const long part = cut_after(third, bytes, bytes.size() / 2);
    ASSERT_GT(part, 0);
    std::string changed = bytes;
    changed[static_cast<std::size_t>(part) / 2] ^= 0x20;
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(third, bytes.size() - part, part, prefix(sha256_of(changed.substr(0, static_cast<std::size_t>(part))))));
        EXPECT_EQ(raw.read_status(), 412);
    }
    const p::Message m = r->read();
    EXPECT_EQ(code_of(m), p::ErrorCode::interrupted);
    EXPECT_NE(std::get<p::Error>(m).message.find("not the start of this file"), std::string::npos)
        << std::get<p::Error>(m).message;
    EXPECT_EQ(held(third), -1) << "the link ends";
    EXPECT_TRUE(folder_names(folder).empty()) << "nothing kept";

    const std::string fourth = accepted_upload(*r, bytes, "p15");
    const long got = cut_after(fourth, bytes, bytes.size() / 2);
    ASSERT_GT(got, 0);
    std::string upper = sha256_of(bytes.substr(0, static_cast<std::size_t>(got)));
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(fourth, bytes.size() - got, got, prefix(upper)) + bytes.substr(got));
        EXPECT_EQ(raw.read_status(), 200);
    }
    const p::Message done = r->read();
    ASSERT_NE(std::get_if<p::PutStatus>(&done), nullptr) << p::type_name(done);
    EXPECT_TRUE(umf::test::file_text(folder / "report.pdf") == bytes);
}

// A put without its SHA-256: every byte arrived is answered 202 and the
// link waits for the hash (Upload-SHA256); a wrong one ends the put with
// nothing kept, the right one (in capitals too, on a resumed request that
// brings the rest) stores the file.
TEST_F(PutServer, AHashNamedAfterTheBytesIsCheckedBeforeTheFileIsStored) {
    auto r = requester();
    std::string bytes(300000, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 13 + (i >> 10));
    const std::string named = "Upload-SHA256: " + sha256_of(bytes) + "\r\n";
    const std::string size = std::to_string(bytes.size());

    const std::string path = accepted_upload(*r, bytes, "p20", PutAnswer::save, "report.pdf", true);
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(path, bytes.size()) + bytes);
        EXPECT_EQ(raw.read_status(), 202) << "all bytes, no hash";
    }
    EXPECT_EQ(held(path), static_cast<long>(bytes.size()));
    EXPECT_EQ(folder_names(folder).size(), 1u) << "only the hidden temporary file";
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(path, 0, bytes.size(), "Upload-SHA256: " + sha256_of("other") + "\r\n"));
        EXPECT_EQ(raw.read_status(), 400);
    }
    EXPECT_EQ(code_of(r->read()), p::ErrorCode::interrupted);
    EXPECT_EQ(held(path), -1);
    EXPECT_TRUE(folder_names(folder).empty()) << "nothing kept";

    const std::string second = accepted_upload(*r, bytes, "p21", PutAnswer::save, "report.pdf", true);
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(second, bytes.size()) + bytes);
        EXPECT_EQ(raw.read_status(), 202);
    }
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(second, 0, bytes.size(), named));
        EXPECT_EQ(raw.read_status(), 200);
    }
    const p::Message done = r->read();
    ASSERT_NE(std::get_if<p::PutStatus>(&done), nullptr) << p::type_name(done);
    EXPECT_TRUE(umf::test::file_text(folder / "report.pdf") == bytes);

    const std::string third = accepted_upload(*r, bytes, "p22", PutAnswer::save, "report.pdf", true);
    const long got = cut_after(third, bytes, bytes.size() / 2);
    ASSERT_GT(got, 0);
    std::string upper = sha256_of(bytes);
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(third, bytes.size() - got, got, "Upload-SHA256: " + upper + "\r\n") + bytes.substr(got));
        EXPECT_EQ(raw.read_status(), 200) << "named with the rest";
    }
    const p::Message stored = r->read();
    ASSERT_NE(std::get_if<p::PutStatus>(&stored), nullptr) << p::type_name(stored);
    EXPECT_EQ(std::get<p::PutStatus>(stored).name, std::optional<std::string>("report (1).pdf"));
    EXPECT_TRUE(umf::test::file_text(folder / "report (1).pdf") == bytes);

    // A put that carried its hash: another one named later is refused.
    const std::string fourth = accepted_upload(*r, bytes, "p23");
    {
        RawTls raw(server->port(), identity.fingerprint);
        // The header alone: it is refused before the body.
        raw.write(request_head(fourth, bytes.size(), std::nullopt, "Upload-SHA256: " + sha256_of("other") + "\r\n"));
        EXPECT_EQ(raw.read_status(), 400);
    }
    EXPECT_EQ(code_of(r->read()), p::ErrorCode::bad_request);
}

// Nobody sends the rest within the link's lifetime: the put is interrupted
// for its session, and nothing is left in the folder.
TEST_F(PutServer, AnUploadNotResumedInTimeIsInterruptedAndNothingIsLeft) {
    upload_ttl = std::chrono::milliseconds(800);
    start();
    auto r = requester();
    const std::string bytes(200000, 'q');
    const std::string path = accepted_upload(*r, bytes, "p9");
    EXPECT_GT(cut_after(path, bytes, bytes.size() / 2), 0);
    const p::Message m = r->read();
    EXPECT_EQ(code_of(m), p::ErrorCode::interrupted);
    EXPECT_EQ(std::get<p::Error>(m).id, p::RequestId{std::string("p9")});
    EXPECT_NE(std::get<p::Error>(m).message.find("was not resumed within"), std::string::npos)
        << std::get<p::Error>(m).message;
    EXPECT_TRUE(folder_names(folder).empty());
    EXPECT_EQ(curl_upload(path, bytes).status, 404);
}

TEST_F(PutServer, AWrongOrMissingLengthIsRefusedAndUsesTheLink) {
    auto r = requester();
    const std::string bytes = "twelve bytes";
    const std::string path = accepted_upload(*r, bytes, "p10");
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write(request_head(path, bytes.size() + 1) + bytes);
        EXPECT_EQ(raw.read_status(), 400);
    }
    EXPECT_EQ(code_of(r->read()), p::ErrorCode::interrupted);
    EXPECT_EQ(curl_upload(path, bytes).status, 404) << "the link is used";

    const std::string chunked_path = accepted_upload(*r, bytes, "p11");
    {
        RawTls raw(server->port(), identity.fingerprint);
        raw.write("PUT " + chunked_path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\nc\r\n" +
                  bytes + "\r\n0\r\n\r\n");
        EXPECT_EQ(raw.read_status(), 411);
    }
    EXPECT_EQ(code_of(r->read()), p::ErrorCode::interrupted);
    EXPECT_TRUE(folder_names(folder).empty());
}

TEST_F(PutServer, UnknownLinksAreNotFoundAndOtherMethodsRefused) {
    const PutResponse unknown = curl_upload("/up/AAAAAAAAAAAAAAAAAAAAAA", "x");
    EXPECT_EQ(unknown.status, 404);
    const auto error = p::parse_error_body(unknown.body);
    ASSERT_TRUE(error) << unknown.body;
    EXPECT_EQ(error->code, p::ErrorCode::not_found);
    EXPECT_EQ(curl_upload("/up/", "x").status, 404);
    const auto r = run_command("curl -s -k --max-time 10 -o /dev/null -w '%{http_code}' 'https://127.0.0.1:" +
                               std::to_string(server->port()) + "/up/AAAAAAAAAAAAAAAAAAAAAA'");
    EXPECT_EQ(std::atoi(r.out.c_str()), 405);
    EXPECT_TRUE(folder_names(folder).empty());
}

TEST_F(PutServer, AWrongTokenSessionCannotPut) {
    Requester r(server->port(), identity.fingerprint);
    ASSERT_FALSE(r.connect());
    ASSERT_FALSE(r.send(p::Hello{std::nullopt, "wrong-token-0123456789abcdef", "x", std::nullopt}));
    EXPECT_EQ(code_of(r.read()), p::ErrorCode::unauthorized);
    r.send(file_put("x", "p12"));
    EXPECT_TRUE(decider->offers(0).empty());
}

TEST_F(PutServer, ATrustedDeviceIsNotAskedTheSecondTime) {
    auto r = requester("phone-42");
    ASSERT_FALSE(r->send(file_put("one", "p13")));
    r->read();  // asking
    decider->answer(decider->offers(1).at(0).id, {PutAnswer::save, true});
    EXPECT_EQ(std::get<p::PutStatus>(r->read()).status, p::PutState::upload);
    ASSERT_FALSE(r->send(file_put("two", "p14")));
    const p::Message m = r->read();
    EXPECT_EQ(std::get<p::PutStatus>(m).status, p::PutState::upload) << "no asking";
    EXPECT_EQ(decider->offers(0).size(), 1u);
    // After a restart too: the device is kept in the config dir.
    start();
    auto again = requester("phone-42");
    ASSERT_FALSE(again->send(file_put("three", "p15")));
    EXPECT_EQ(std::get<p::PutStatus>(again->read()).status, p::PutState::upload);
    EXPECT_EQ(decider->offers(0).size(), 1u);
}

TEST_F(PutServer, ASessionThatLeavesWhileAskingWithdrawsTheOffer) {
    auto r = requester();
    ASSERT_FALSE(r->send(file_put("bytes", "p16")));
    r->read();  // asking
    const auto id = decider->offers(1).at(0).id;
    r.reset();
    EXPECT_TRUE(decider->withdrawn(id));
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
