// The provider's HTTPS side with an independent client (curl): one-time
// downloads of what a grab resolved, the page, and nothing else — no path a
// client sends reaches the file system, whatever its spelling.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "native/sha256.hpp"
#include "provider/content/board_resolver.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/service/static_site.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/field/field_io.hpp"
#include "shared/protocol/http_error_body.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using umf::test::TempDir;

namespace fs = std::filesystem;
namespace p = umf::protocol;
using namespace umf::provider;
using umf::test::run_command;

constexpr const char* kHttpToken = "http-test-token-0123456789ab";

struct HttpResponse {
    int status = 0;
    std::string body;
    std::string headers;
};

class ProviderHttp : public ::testing::Test {
protected:
    TempDir dir;
    fs::path big;
    std::shared_ptr<Service> service;
    std::unique_ptr<Server> server;

    static void SetUpTestSuite() {
        if (run_command("curl --version >/dev/null 2>&1").exit_code != 0) GTEST_SKIP() << "curl is not installed";
    }
    void SetUp() override {
        big = dir.path / "big file.bin";
        {
            std::ofstream out(big, std::ios::binary);
            std::string chunk(1 << 20, '\0');
            for (std::size_t i = 0; i < chunk.size(); ++i) chunk[i] = static_cast<char>(i * 7 + 3);
            for (int i = 0; i < 24; ++i) out << chunk;
        }
        std::ofstream(dir.path / "secret.txt") << "not for requesters";
        Board board;
        board.items.push_back({"Big", big, std::nullopt, std::nullopt, std::nullopt});
        auto resolver = std::make_shared<BoardResolver>(board, std::vector<PixelRect>{{0, 0, 1920, 1080}});
        service = std::make_shared<Service>(default_service_config(), kHttpToken,
                                            std::vector<std::shared_ptr<const Resolver>>{resolver});
        const TlsIdentity identity = load_or_create_tls_identity(dir.path / "cfg");
        server = make_server(service, identity);
        server->start();
    }
    // The content a grab over the WebSocket would get, and its link.
    p::Content grab_content() {
        SessionState state;
        service->handle_text(state, p::encode(p::Hello{std::nullopt, kHttpToken, "t"}));
        const auto out = service->handle_text(state, p::encode(p::Grab{p::RequestId{std::string("g")}, {5, 5}}));
        return std::get<p::Content>(out.replies.at(0));
    }
    std::string grab_link() { return *grab_content().download; }
    std::string read_big() {
        std::ifstream in(big, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), {}};
    }
    HttpResponse curl(const std::string& target, const std::string& options = "") {
        const fs::path body = dir.path / "body", headers = dir.path / "headers";
        fs::remove(body);
        const auto r = run_command("curl -s -k --path-as-is --max-time 20 " + options + " -o '" + body.string() +
                                   "' -D '" + headers.string() + "' -w '%{http_code}' 'https://127.0.0.1:" +
                                   std::to_string(server->port()) + target + "'");
        HttpResponse out;
        out.status = std::atoi(r.out.c_str());
        std::ifstream b(body, std::ios::binary), h(headers);
        out.body.assign(std::istreambuf_iterator<char>(b), {});
        out.headers.assign(std::istreambuf_iterator<char>(h), {});
        return out;
    }
    // A download link's request, with the grabbing session's token.
    HttpResponse download(const std::string& link, const std::string& options = "") {
        return curl(link, "-H 'Authorization: Bearer " + std::string(kHttpToken) + "' " + options);
    }
    bool sessions_drain() {
        for (int i = 0; i < 200 && server->connection_count() > 0; ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
        return server->connection_count() == 0;
    }
};

// A link is of no use without the pairing token of the session that
// grabbed it: 401 with the reason, no byte of the file, and the link stays
// for its owner.
TEST_F(ProviderHttp, ADownloadLinkAsksForTheGrabbingSessionsToken) {
    const std::string link = grab_link();
    for (const std::string& options : std::vector<std::string>
         {std::string(), std::string("-H 'Authorization: Bearer wrong-token-0123456789abcdef'"),
          "-H 'Authorization: Basic " + std::string(kHttpToken) + "'", std::string("-H 'Authorization: Bearer'")}) {
        const HttpResponse refused = curl(link, options);
        EXPECT_EQ(refused.status, 401) << options;
        const auto error = p::parse_error_body(refused.body);
        ASSERT_TRUE(error) << refused.body;
        EXPECT_EQ(error->code, p::ErrorCode::unauthorized);
        EXPECT_NE(refused.body.find("Authorization: Bearer"), std::string::npos) << refused.body;
    }
    const HttpResponse owner = curl(link, "-H 'authorization: bearer " + std::string(kHttpToken) + "'");
    EXPECT_EQ(owner.status, 200) << "the scheme is case-insensitive, and the link outlived the refusals";
    EXPECT_EQ(owner.body.size(), fs::file_size(big));
}

TEST_F(ProviderHttp, ADownloadLinkEndsWhenItsDownloadCompletes) {
    const std::string link = grab_link();
    const HttpResponse first = download(link);
    EXPECT_EQ(first.status, 200);
    EXPECT_EQ(first.body.size(), fs::file_size(big));
    std::ifstream in(big, std::ios::binary);
    const std::string expected{std::istreambuf_iterator<char>(in), {}};
    EXPECT_TRUE(first.body == expected) << "the bytes differ";
    EXPECT_NE(first.headers.find("Content-Disposition: attachment; filename=\"big file.bin\"; filename*=UTF-8''big%20file.bin"),
              std::string::npos)
        << first.headers;
    EXPECT_NE(first.headers.find("Content-Type: application/octet-stream"), std::string::npos);
    EXPECT_NE(first.headers.find("Cache-Control: no-store"), std::string::npos);

    const HttpResponse second = download(link);
    EXPECT_EQ(second.status, 404);
    const auto error = p::parse_error_body(second.body);
    ASSERT_TRUE(error) << second.body;
    EXPECT_EQ(error->code, p::ErrorCode::not_found);
}

TEST_F(ProviderHttp, NoClientPathReachesTheFileSystem) {
    EXPECT_EQ(curl("/").status, 200);
    for (const std::string& target : std::vector<std::string>{"/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd", "//etc/passwd", "/dl/../index.html",
          "/dl/..%2f..%2fetc%2fpasswd", "/dl/" + (dir.path / "secret.txt").string(), "/secret.txt",
          "/provider-key.pem", "/dl/AAAAAAAAAAAAAAAAAAAAAA", "/index.html/..", "/\\..\\etc\\passwd"}) {
        const HttpResponse r = curl(target);
        EXPECT_EQ(r.status, 404) << target;
        EXPECT_EQ(r.body.find("not for requesters"), std::string::npos) << target;
        EXPECT_EQ(r.body.find("root:"), std::string::npos) << target;
    }
    EXPECT_EQ(curl("/", "-X POST --data x=1").status, 405);
    EXPECT_EQ(curl("/", "-X DELETE").status, 405);
    EXPECT_EQ(curl("/", "-H 'X-Big: " + std::string(9000, 'a') + "'").status, 431);
    EXPECT_EQ(server->connection_count() > 100, false);
}

TEST_F(ProviderHttp, PagesCarryAContentSecurityPolicyForAWasmWorker) {
    const HttpResponse page = curl("/");
    EXPECT_EQ(page.status, 200);
    const auto at = page.headers.find("Content-Security-Policy: ");
    ASSERT_NE(at, std::string::npos) << page.headers;
    const std::string csp = page.headers.substr(at, page.headers.find('\r', at) - at);
    for (const std::string& part :
         {std::string("default-src 'self'"), std::string("script-src 'self' 'wasm-unsafe-eval'"),
          std::string("worker-src 'self' blob:"),
          "connect-src 'self' wss://127.0.0.1:" + std::to_string(server->port()) + " https://*.local:*;",
          std::string("object-src 'none'"),
          std::string("style-src 'self';"), std::string("frame-ancestors 'none'")})
        EXPECT_NE(csp.find(part), std::string::npos) << part << "\n" << csp;
    EXPECT_EQ(page.body.find("style="), std::string::npos) << "no inline style under style-src 'self'";
    const HttpResponse style = curl("/umf-provider.css");
    EXPECT_EQ(style.status, 200);
    EXPECT_NE(style.headers.find("Content-Type: text/css; charset=utf-8"), std::string::npos) << style.headers;
    // A Host that is not a plain host:port adds nothing to the policy.
    const HttpResponse odd = curl("/", "-H 'Host: a b;script-src *'");
    EXPECT_EQ(odd.headers.find("script-src *"), std::string::npos) << odd.headers;
}

// What a page pointed at another screen asks (docs/PROTOCOL.md, "Nearby
// screens"): its own screen's list of the others, and their fields, which
// pages of any origin may read; neither needs the token.
TEST_F(ProviderHttp, NearbyScreensAndTheFieldAreServedWithoutAToken) {
    const HttpResponse none = curl("/nearby.json");
    EXPECT_EQ(none.status, 200);
    EXPECT_EQ(none.body, R"({"screens":[]})");
    EXPECT_NE(none.headers.find("Content-Type: application/json"), std::string::npos) << none.headers;
    EXPECT_NE(none.headers.find("Cache-Control: no-store"), std::string::npos) << none.headers;
    EXPECT_EQ(none.headers.find("Access-Control-Allow-Origin"), std::string::npos) << "the list is for its own page";

    const HttpResponse field = curl("/field.json", "-H 'Origin: https://other.local:8443'");
    EXPECT_EQ(field.status, 200);
    EXPECT_NE(field.headers.find("Access-Control-Allow-Origin: *"), std::string::npos) << field.headers;
    EXPECT_EQ(umf::field_to_json(umf::parse_field(field.body)), umf::field_to_json(service->screens()->field.definition));
    EXPECT_EQ(curl("/field.json", "-I").status, 200);
    EXPECT_EQ(curl("/field.json", "-X POST --data x").status, 405);

    // A provider that browsed two other screens lists them.
    auto nearby = std::make_shared<NearbyScreens>();
    nearby->set({{"umf on b", "https://b.local:9443", std::string(64, 'b')},
                 {"umf on \"a\"", "https://a.local:8443", std::string(64, 'a')}});
    ServiceConfig config = default_service_config();
    config.nearby = nearby;
    server->stop();
    service = std::make_shared<Service>(std::move(config), kHttpToken);
    server = make_server(service, load_or_create_tls_identity(dir.path / "cfg"));
    server->start();
    const HttpResponse two = curl("/nearby.json");
    EXPECT_EQ(two.status, 200);
    EXPECT_EQ(two.body, R"({"screens":[{"name":"umf on b","origin":"https://b.local:9443","fingerprint":")" +
                            std::string(64, 'b') + R"("},{"name":"umf on \"a\"","origin":"https://a.local:8443",)"
                            R"("fingerprint":")" + std::string(64, 'a') + R"("}]})");
}

TEST(StaticSite, TypesOfTheWebClientsFiles) {
    TempDir site;
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"app.js", "text/javascript; charset=utf-8"},
        {"worker.mjs", "text/javascript; charset=utf-8"},
        {"umf-detector.wasm", "application/wasm"},
        {"fields/b4.json", "application/json; charset=utf-8"},
        {"manifest.webmanifest", "application/manifest+json"},
        {"icon.svg", "image/svg+xml"},
        {"icon.png", "image/png"},
        {"style.css", "text/css; charset=utf-8"},
        {"about.html", "text/html; charset=utf-8"},
        {"favicon.ico", "image/x-icon"}};
    for (const auto& [name, mime] : expected) {
        fs::create_directories((site.path / name).parent_path());
        std::ofstream(site.path / name) << name;
    }
    std::ofstream(site.path / ".hidden") << "no";
    const StaticSite from = StaticSite::from_folder(site.path);
    for (const auto& [name, mime] : expected) {
        const auto file = from.find("/" + name + "?v=1");
        ASSERT_TRUE(file) << name;
        EXPECT_EQ(file->mime, mime) << name;
        EXPECT_EQ(*file->bytes, name);
    }
    EXPECT_FALSE(from.find("/.hidden"));
    // No index.html of its own (a client still being built): "/" is the built-in page.
    const auto index = from.find("/");
    ASSERT_TRUE(index);
    EXPECT_NE(index->bytes->find("umf provider"), std::string::npos);
    std::ofstream(site.path / "index.html") << "the client";
    EXPECT_EQ(*StaticSite::from_folder(site.path).find("/")->bytes, "the client");
    EXPECT_FALSE(StaticSite::from_folder(site.path).find("/umf-provider.css"));
}

TEST_F(ProviderHttp, PlainHttpIsToldToUseHttps) {
    const auto r = run_command("curl -s --max-time 5 -w '\\n%{http_code}' http://127.0.0.1:" + std::to_string(server->port()) + "/");
    EXPECT_NE(r.out.find("This is an HTTPS server"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("400"), std::string::npos) << r.out;
    EXPECT_EQ(curl("/").status, 200) << "TLS still works";
}

// A download cut off keeps its link: the rest is asked for with Range and
// If-Range naming the ETag, and comes as 206 from where the cut left it;
// the two parts are the file. Then the link is used up.
TEST_F(ProviderHttp, ADownloadCutOffResumesWhereItStopped) {
    // 24 MiB read at 1 MiB/s, abandoned after half a second.
    const p::Content offered = grab_content();
    const std::string link = *offered.download;
    const HttpResponse cut = download(link, "--limit-rate 1M --max-time 0.5");
    ASSERT_LT(cut.body.size(), fs::file_size(big));
    const std::string etag = "\"sha256-" + *offered.sha256 + "\"";
    EXPECT_NE(cut.headers.find("ETag: " + etag), std::string::npos) << cut.headers;
    EXPECT_NE(cut.headers.find("Accept-Ranges: bytes"), std::string::npos) << cut.headers;
    EXPECT_TRUE(sessions_drain()) << server->connection_count() << " connections still open";

    const std::size_t have = cut.body.size();
    const HttpResponse rest =
        download(link, "-H 'Range: bytes=" + std::to_string(have) + "-' -H 'If-Range: " + etag + "'");
    EXPECT_EQ(rest.status, 206);
    EXPECT_NE(rest.headers.find("Content-Range: bytes " + std::to_string(have) + "-" +
                                std::to_string(fs::file_size(big) - 1) + "/" + std::to_string(fs::file_size(big))),
              std::string::npos)
        << rest.headers;
    EXPECT_TRUE(cut.body + rest.body == read_big()) << "the parts are not the file";
    EXPECT_EQ(download(link).status, 404) << "a completed download ends the link";
    EXPECT_EQ(fs::file_size(big), 24u << 20) << "the file is untouched";
}

// What a resume request may get instead of the rest: the whole file when its
// If-Range names another version, 416 past the end; a HEAD leaves the link.
TEST_F(ProviderHttp, ResumeRequestsThatCannotBeMetGetTheWholeOrAReason) {
    const p::Content offered = grab_content();
    const std::string link = *offered.download;
    EXPECT_EQ(download(link, "-I").status, 200);
    const HttpResponse other = download(link, "-H 'Range: bytes=100-' -H 'If-Range: \"sha256-0000\"'");
    EXPECT_EQ(other.status, 200);
    EXPECT_TRUE(other.body == read_big()) << "another version's resume gets the whole file";

    const p::Content again = grab_content();
    const HttpResponse past = download(*again.download, "-H 'Range: bytes=" + std::to_string(fs::file_size(big)) + "-'");
    EXPECT_EQ(past.status, 416);
    EXPECT_NE(past.headers.find("Content-Range: bytes */" + std::to_string(fs::file_size(big))), std::string::npos)
        << past.headers;
    EXPECT_EQ(download(*again.download).status, 200) << "a request that was not met leaves the link";
}

// One byte changed after the grab, the size and modification time kept (as
// a tool that restores times leaves it): the download is cut before its
// last piece, so the phone never holds bytes other than the announced ones,
// and the next grab announces the new SHA-256.
TEST_F(ProviderHttp, AFileChangedInPlaceAfterTheGrabIsCutNotSent) {
    const p::Content offered = grab_content();
    const auto mtime = fs::last_write_time(big);
    {
        std::fstream f(big, std::ios::binary | std::ios::in | std::ios::out);
        f.seekp(12345);
        f.put('\x7f');
    }
    fs::last_write_time(big, mtime);
    const std::string changed = read_big();
    const HttpResponse cut = download(*offered.download);
    EXPECT_LT(cut.body.size(), changed.size()) << "the changed file went out whole";
    EXPECT_TRUE(sessions_drain());

    const p::Content again = grab_content();
    umf::native::Sha256 sha;
    sha.update(changed.data(), changed.size());
    const std::string now = sha.hex();
    EXPECT_NE(*offered.sha256, now);
    EXPECT_EQ(*again.sha256, now) << "the next grab hashed the file again";
    const HttpResponse whole = download(*again.download);
    EXPECT_EQ(whole.status, 200);
    EXPECT_TRUE(whole.body == changed) << "the file as it is now, whole";
}

// Changed with a new modification time (or replaced): refused before a byte.
TEST_F(ProviderHttp, AFileRewrittenAfterTheGrabIsRefusedWithItsReason) {
    const p::Content offered = grab_content();
    std::string bytes = read_big();
    bytes[0] ^= 1;
    const fs::path next = dir.path / "next.bin";
    std::ofstream(next, std::ios::binary) << bytes;
    fs::rename(next, big);
    const HttpResponse r = download(*offered.download);
    EXPECT_EQ(r.status, 409);
    const auto error = p::parse_error_body(r.body);
    ASSERT_TRUE(error) << r.body;
    EXPECT_NE(error->message.find("changed since it was offered"), std::string::npos) << error->message;
}

}  // namespace

#endif
