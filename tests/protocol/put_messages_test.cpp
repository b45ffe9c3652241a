// The put messages (docs/PROTOCOL.md, "Put"): put, put_status, hello's
// device, welcome's features, and the error codes that answer only puts.
#include <gtest/gtest.h>

#include <string>

#include "shared/protocol/messages.hpp"

using namespace umf::protocol;

namespace {

const std::string kSha(64, 'a');

std::string file_put(const std::string& extra = "", const std::string& without = "") {
    std::string text = R"({"type":"put","v":1,"id":"p2","point":[31.5,17.1],"kind":"file")";
    if (without != "name") text += R"(,"name":"report.pdf")";
    if (without != "mime") text += R"(,"mime":"application/pdf")";
    if (without != "size") text += R"(,"size":2411724)";
    if (without != "sha256") text += R"(,"sha256":")" + kSha + "\"";
    return text + extra + "}";
}

ProtocolError put_refused(const std::string& text) {
    auto r = parse_message(text);
    if (const auto* e = std::get_if<ProtocolError>(&r)) return *e;
    ADD_FAILURE() << "accepted: " << text;
    return {};
}

void expect_bad(const std::string& text, const std::string& words) {
    const ProtocolError e = put_refused(text);
    EXPECT_EQ(e.code, ErrorCode::bad_request) << text;
    EXPECT_NE(e.message.find(words), std::string::npos) << e.message << "\nexpected: " << words << "\n" << text;
}

Message accepted(const std::string& text, const ParseLimits& limits = {}) {
    auto r = parse_message(text, limits);
    if (const auto* e = std::get_if<ProtocolError>(&r)) {
        ADD_FAILURE() << "refused: " << e->message << "\n" << text;
        return Seeking{};
    }
    return std::get<Message>(r);
}

}  // namespace

TEST(PutMessages, TheSpecExamplesParse) {
    const Message url = accepted(
        R"({"type":"put","v":1,"id":"p1","point":[31.5,17.1],"kind":"url","url":"https://example.org/talk","title":"Talk page"})");
    const auto& u = std::get<Put>(url);
    EXPECT_EQ(u.kind, ContentKind::url);
    EXPECT_EQ(u.url, "https://example.org/talk");
    EXPECT_EQ(u.title, "Talk page");
    EXPECT_TRUE(is_request(url));

    const Put f = std::get<Put>(accepted(file_put()));
    EXPECT_EQ(f.id, RequestId{std::string("p2")});
    EXPECT_EQ(f.name, "report.pdf");
    EXPECT_EQ(f.size, 2411724);
    EXPECT_EQ(f.sha256, kSha);
    EXPECT_EQ(f.title, "");

    const auto statuses = {
        R"({"type":"put_status","v":1,"id":"p2","status":"asking"})",
        R"({"type":"put_status","v":1,"id":"p2","status":"upload","upload":"/up/Qm9vdGggYW5kIHdpbmRvdw"})",
        R"({"type":"put_status","v":1,"id":"p2","status":"done","outcome":"saved","name":"report (1).pdf"})",
        R"({"type":"put_status","v":1,"id":"p1","status":"done","outcome":"opened"})"};
    for (const char* text : statuses) {
        const Message m = accepted(text, kRequesterLimits);
        ASSERT_TRUE(std::holds_alternative<PutStatus>(m)) << text;
        EXPECT_FALSE(is_request(m));
        EXPECT_EQ(encode(m), text) << "encodes back to the same text";
    }
}

TEST(PutMessages, RefusesMalformedPuts) {
    expect_bad(R"({"type":"put","v":1,"point":[1,1],"kind":"url","url":"https://a.example/"})", "needs an \"id\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","kind":"url","url":"https://a.example/"})", "missing \"point\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1],"kind":"url","url":"https://a.example/"})", "\"point\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,2e6],"kind":"url","url":"https://a.example/"})", "\"point\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"url":"https://a.example/"})", "\"kind\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"snapshot"})", "\"url\" or \"file\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"none"})", "\"url\" or \"file\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"teleport"})", "\"kind\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"url"})", "a url put needs \"url\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"url","url":"javascript:alert-1"})", "\"url\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"url","url":"https://a.example/ b"})", "\"url\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"url","url":"https://a.example/","title":7})",
               "\"title\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"url","url":"https://a.example/","title":")" +
                   std::string(kMaxTitleBytes + 1, 't') + "\"}",
               "\"title\"");
    expect_bad(R"({"type":"put","v":1,"id":"p","point":[1,1],"kind":"url","url":")" + std::string("https://") +
                   std::string(kMaxUrlBytes, 'u') + "\"}",
               "\"url\"");
    for (const char* member : {"name", "mime", "size"})
        expect_bad(file_put("", member), std::string("a file put needs \"") + member + "\"");
    EXPECT_FALSE(std::get<Put>(accepted(file_put("", "sha256"))).sha256) << "the upload may name it after the bytes";
    // Each file member malformed.
    auto with = [](const std::string& member, const std::string& value) {
        std::string text = file_put("", member);
        text.pop_back();
        return text + ",\"" + member + "\":" + value + "}";
    };
    expect_bad(with("name", R"("../etc/passwd")"), "\"name\"");
    expect_bad(with("name", R"("a\\b")"), "\"name\"");
    expect_bad(with("name", R"("..")"), "\"name\"");
    expect_bad(with("name", R"("")"), "\"name\"");
    expect_bad(with("name", R"("a\u0007b")"), "\"name\"");
    expect_bad(with("name", "\"" + std::string(kMaxFileNameBytes + 1, 'n') + "\""), "\"name\"");
    expect_bad(with("mime", R"("pdf")"), "\"mime\"");
    expect_bad(with("mime", R"("application/")"), "\"mime\"");
    expect_bad(with("size", "-1"), "\"size\"");
    expect_bad(with("size", "1.5"), "\"size\"");
    expect_bad(with("size", "9007199254740992"), "\"size\"");
    expect_bad(with("size", R"("12")"), "\"size\"");
    expect_bad(with("sha256", "\"" + std::string(63, 'a') + "\""), "\"sha256\"");
    expect_bad(with("sha256", "\"" + std::string(64, 'A') + "\""), "\"sha256\"");
    expect_bad(with("sha256", "\"" + std::string(64, 'g') + "\""), "\"sha256\"");
    // The id comes back with the error whenever it could be read.
    EXPECT_EQ(put_refused(with("size", "-1")).id, RequestId{std::string("p2")});
    // Limits and version as for every message.
    EXPECT_EQ(put_refused(file_put(",\"pad\":\"" + std::string(kMaxRequestBytes, 'x') + "\"")).code, ErrorCode::too_large);
    EXPECT_EQ(put_refused(R"({"type":"put","v":2,"id":"p","point":[1,1],"kind":"url","url":"https://a.example/"})").code,
              ErrorCode::unsupported_version);
}

TEST(PutMessages, RefusesMalformedPutStatus) {
    auto bad = [](const std::string& text, const std::string& words) {
        auto r = parse_message(text, kRequesterLimits);
        const auto* e = std::get_if<ProtocolError>(&r);
        ASSERT_NE(e, nullptr) << "accepted: " << text;
        EXPECT_EQ(e->code, ErrorCode::bad_request);
        EXPECT_NE(e->message.find(words), std::string::npos) << e->message << "\nexpected: " << words;
    };
    bad(R"({"type":"put_status","v":1,"status":"asking"})", "needs an \"id\"");
    bad(R"({"type":"put_status","v":1,"id":"p"})", "\"status\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"thinking"})", "\"status\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"upload"})", "needs \"upload\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"upload","upload":"//evil.example/x"})", "\"upload\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"upload","upload":"https://evil.example/x"})", "\"upload\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"upload","upload":"/up/a b"})", "\"upload\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"done"})", "needs \"outcome\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"done","outcome":"burned"})", "\"outcome\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"done","outcome":"saved"})", "needs \"name\"");
    bad(R"({"type":"put_status","v":1,"id":"p","status":"done","outcome":"saved","name":"a/b"})", "\"name\"");
}

TEST(PutMessages, HelloDeviceIsPrintableAscii) {
    const std::string head = R"({"type":"hello","v":1,"token":"tok","client":"c")";
    EXPECT_EQ(std::get<Hello>(accepted(head + "}")).device, std::nullopt);
    EXPECT_EQ(std::get<Hello>(accepted(head + ",\"device\":null}")).device, std::nullopt);
    EXPECT_EQ(std::get<Hello>(accepted(head + ",\"device\":\"Pixel 7 ~a1\"}")).device, "Pixel 7 ~a1");
    EXPECT_EQ(std::get<Hello>(accepted(head + ",\"device\":\"" + std::string(64, 'd') + "\"}")).device,
              std::string(64, 'd'));
    expect_bad(head + ",\"device\":\"\"}", "\"device\"");
    expect_bad(head + ",\"device\":\"" + std::string(65, 'd') + "\"}", "\"device\"");
    expect_bad(head + ",\"device\":\"caf\xc3\xa9\"}", "\"device\"");
    expect_bad(head + ",\"device\":\"a\\tb\"}", "\"device\"");
    expect_bad(head + ",\"device\":\"a\\u007fb\"}", "\"device\"");
    expect_bad(head + ",\"device\":5}", "\"device\"");
    // Encoding refuses what parsing would.
    Hello h{std::nullopt, "tok", "c", std::string("bad\x01")};
    EXPECT_THROW(encode(h), std::invalid_argument);
}

TEST(PutMessages, NewErrorCodesHaveNames) {
    EXPECT_STREQ(to_string(ErrorCode::refused), "refused");
    EXPECT_STREQ(to_string(ErrorCode::interrupted), "interrupted");
    EXPECT_EQ(error_code_from_string("refused"), ErrorCode::refused);
    EXPECT_EQ(error_code_from_string("interrupted"), ErrorCode::interrupted);
    const auto e = accepted(R"({"type":"error","v":1,"id":"p2","code":"interrupted","message":"cut"})", kRequesterLimits);
    EXPECT_EQ(std::get<Error>(e).code, ErrorCode::interrupted);
}
