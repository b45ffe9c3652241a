#include "shared/protocol/messages.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "shared/field/field_io.hpp"
#include "shared/protocol/json_checks.hpp"
#include "tests/support/replaced.hpp"

using namespace umf;
using namespace umf::protocol;

namespace {

using umf::test::replaced;

Field shipped_field() { return load_field(std::string(UMF_DATA_DIR) + "/fields/b4-64x36.json"); }

Welcome sample_welcome() {
    Welcome w;
    w.id = RequestId{std::int64_t{1}};
    w.provider = {"desk-1", "umf-provider/0.1.0"};
    w.field.definition = shipped_field();
    w.field.screens = {{"DP-1", {0, 0, 32, 36}, 1920, 2160}, {"HDMI-1 \xe2\x80\x94 TV", {32, 0, 64, 36}, 1920, 2160}};
    w.overlay = {"balanced", 0.1, 0.4, 1.5, PulseWaveform::sine};
    w.limits = Limits{};
    return w;
}

Content sample_file() {
    Content c;
    c.id = RequestId{std::string("g-7")};
    c.kind = ContentKind::file;
    c.title = "report.pdf \xe2\x80\x94 Document Viewer";
    c.name = "report.pdf";
    c.mime = "application/pdf";
    c.size = 123456;
    c.sha256 = std::string(64, 'a');
    c.download = "/dl/Zm9vYmFyYmF6";
    return c;
}

// One of each type, and the optional members both present and absent.
std::vector<Message> samples() {
    std::vector<Message> out;
    out.push_back(Hello{RequestId{std::string("h")}, "tok_-123abcDEF", "umf-web/0.1 (Android; Chrome 120)"});
    out.push_back(Hello{std::nullopt, std::string(kMaxTokenBytes, 'x'), ""});
    out.push_back(sample_welcome());
    out.push_back(Seeking{});
    out.push_back(Aim{RequestId{std::int64_t{42}}, {31.52, 17.08}, 0.99});
    out.push_back(Aim{std::nullopt, {-0.25, 1e6}, 0.0});
    out.push_back(Target{RequestId{std::int64_t{42}}, {31.52, 17.08}, ContentKind::url, "umf \xe2\x80\x94 GitHub"});
    out.push_back(Target{std::nullopt, {0, 0}, ContentKind::none, ""});
    out.push_back(Grab{RequestId{std::string("g-7")}, {12.5, 3.25}});
    out.push_back(Grab{RequestId{std::int64_t{-kMaxSafeInteger}}, {0, 0}});
    out.push_back(sample_file());
    Content url;
    url.id = RequestId{std::int64_t{9}};
    url.kind = ContentKind::url;
    url.title = "Example";
    url.url = "https://example.org/a?b=c#d";
    out.push_back(url);
    Content snap = sample_file();
    snap.kind = ContentKind::snapshot;
    snap.name = "snapshot.png";
    snap.mime = "image/png";
    snap.sha256.reset();
    out.push_back(snap);
    Content none;
    none.id = RequestId{std::int64_t{0}};
    out.push_back(none);
    for (ErrorCode code : kAllErrorCodes) out.push_back(Error{std::nullopt, code, std::string("because ") + to_string(code)});
    out.push_back(Error{RequestId{std::string("g-7")}, ErrorCode::not_found, "nothing there"});
    // Puts (docs/PROTOCOL.md, "Put"), and the members they added to hello and welcome.
    Hello with_device{RequestId{std::int64_t{1}}, "tok", "umf-web/0.2", std::string("phone-7f3a ~ A")};
    out.push_back(with_device);
    Welcome with_features = sample_welcome();
    with_features.features = {"put", "later-feature"};
    out.push_back(with_features);
    Put url_put;
    url_put.id = RequestId{std::string("p1")};
    url_put.point = {31.5, 17.1};
    url_put.kind = ContentKind::url;
    url_put.url = "https://example.org/talk";
    url_put.title = "Talk page";
    out.push_back(url_put);
    Put file_put;
    file_put.id = RequestId{std::int64_t{2}};
    file_put.point = {-3, 1e6};
    file_put.kind = ContentKind::file;
    file_put.name = "report (draft).pdf";
    file_put.mime = "application/pdf";
    file_put.size = 2411724;
    file_put.sha256 = std::string(64, 'f');
    out.push_back(file_put);
    out.push_back(PutStatus{RequestId{std::string("p2")}, PutState::asking, std::nullopt, std::nullopt, std::nullopt});
    out.push_back(PutStatus{RequestId{std::string("p2")}, PutState::upload, std::string("/up/Qm9vdGggYW5kIHdpbmRvdw"),
                            std::nullopt, std::nullopt});
    out.push_back(PutStatus{RequestId{std::string("p2")}, PutState::done, std::nullopt, PutOutcome::saved,
                            std::string("report (1).pdf")});
    out.push_back(PutStatus{RequestId{std::int64_t{1}}, PutState::done, std::nullopt, PutOutcome::opened, std::nullopt});
    return out;
}

Message parsed(const ParseResult& r) {
    if (const auto* e = std::get_if<ProtocolError>(&r)) {
        ADD_FAILURE() << "refused: " << to_string(e->code) << ": " << e->message;
        return Seeking{};
    }
    return std::get<Message>(r);
}

ProtocolError refused(const std::string& text, const ParseLimits& limits = kRequesterLimits) {
    auto r = parse_message(text, limits);
    if (const auto* e = std::get_if<ProtocolError>(&r)) return *e;
    ADD_FAILURE() << "accepted: " << text.substr(0, 300);
    return {};
}

// The text must be refused with `code` and a message containing `words`.
void expect_refused(const std::string& text, ErrorCode code, const std::string& words,
                    const ParseLimits& limits = kRequesterLimits) {
    ProtocolError e = refused(text, limits);
    EXPECT_EQ(e.code, code) << text.substr(0, 300) << "\nmessage: " << e.message;
    EXPECT_NE(e.message.find(words), std::string::npos)
        << "message: " << e.message << "\nexpected words: " << words << "\ntext: " << text.substr(0, 300);
}

TEST(ProtocolMessages, EveryTypeRoundTrips) {
    std::set<std::string> types;
    for (const Message& m : samples()) {
        std::string text = encode(m);
        Message back = parsed(parse_message(text, kRequesterLimits));
        EXPECT_EQ(back, m) << text.substr(0, 300);
        EXPECT_EQ(encode(back), text);
        types.insert(type_name(m));
    }
    EXPECT_EQ(types.size(), std::variant_size_v<Message>);
}

TEST(ProtocolMessages, WelcomeFeaturesAreAnOptionalListOfStrings) {
    std::string text = encode(sample_welcome());
    EXPECT_EQ(text.find("features"), std::string::npos) << "no features: left out";
    text.pop_back();
    auto with = [&](const std::string& features) { return text + ",\"features\":" + features + "}"; };
    EXPECT_EQ(std::get<Welcome>(parsed(parse_message(with("null"), kRequesterLimits))).features,
              std::vector<std::string>{});
    EXPECT_EQ(std::get<Welcome>(parsed(parse_message(with("[]"), kRequesterLimits))).features,
              std::vector<std::string>{});
    EXPECT_EQ(std::get<Welcome>(parsed(parse_message(with(R"(["put","x"])"), kRequesterLimits))).features,
              (std::vector<std::string>{"put", "x"}));
    expect_refused(with(R"("put")"), ErrorCode::bad_request, "\"features\"");
    expect_refused(with(R"([1])"), ErrorCode::bad_request, "\"features\"");
    expect_refused(with(R"([""])"), ErrorCode::bad_request, "\"features\"");
    expect_refused(with("[\"" + std::string(kMaxFeatureBytes + 1, 'f') + "\"]"), ErrorCode::bad_request,
                   "\"features\"");
    std::string many = "[";
    for (std::size_t i = 0; i <= kMaxFeatures; ++i) many += std::string(i ? "," : "") + "\"f\"";
    expect_refused(with(many + "]"), ErrorCode::bad_request, "\"features\"");
}

TEST(ProtocolMessages, TextIsAVersionedObjectWithTypeFirst) {
    for (const Message& m : samples()) {
        std::string text = encode(m);
        EXPECT_EQ(text.rfind(std::string("{\"type\":\"") + type_name(m) + "\",\"v\":1", 0), 0u) << text.substr(0, 80);
    }
    EXPECT_EQ(encode(Seeking{}), R"({"type":"seeking","v":1})");
    EXPECT_EQ(encode(Grab{RequestId{std::int64_t{3}}, {1.5, 2}}), R"({"type":"grab","v":1,"id":3,"point":[1.5,2.0]})");
}

TEST(ProtocolMessages, RequestsAreTheRequesterSide) {
    for (const Message& m : samples()) {
        std::string type = type_name(m);
        bool request = type == "hello" || type == "seeking" || type == "aim" || type == "grab" || type == "put";
        EXPECT_EQ(is_request(m), request) << type;
    }
}

TEST(ProtocolMessages, WelcomeCarriesTheWholeField) {
    Welcome w = sample_welcome();
    auto doc = nlohmann::json::parse(encode(w));
    EXPECT_EQ(doc["field"]["definition"]["format"], "umf-field/1");
    EXPECT_EQ(doc["field"]["definition"]["rows"].size(), 36u);
    EXPECT_EQ(doc["field"]["screens"][1]["region"], nlohmann::json::parse("[32.0, 0.0, 64.0, 36.0]"));
    // The field file parser reads the embedded definition as it is.
    Field f = parse_field(doc["field"]["definition"].dump());
    EXPECT_EQ(f.modules, w.field.definition.modules);
}

TEST(ProtocolMessages, AWelcomeOfALargeFieldNeedsTheRequesterLimits) {
    Welcome w = sample_welcome();
    w.field.definition = make_field(200, 120, 4, 2, WindowKey::modules, "big");
    w.field.screens = {{"big", {0, 0, 200, 120}, 3840, 2160}};
    std::string text = encode(w);
    EXPECT_GT(text.size(), kMaxRequestBytes);
    EXPECT_EQ(refused(text, ParseLimits{}).code, ErrorCode::too_large);
    EXPECT_EQ(parsed(parse_message(text, kRequesterLimits)), Message{w});
}

TEST(ProtocolMessages, UnknownMembersAndNullsAreIgnored) {
    auto r = parse_message(R"({"type":"aim","v":1,"point":[1,2],"confidence":0.5,"future":{"x":[1,2,3]},
                              "quad":null,"id":null})");
    EXPECT_EQ(parsed(r), Message{(Aim{std::nullopt, {1, 2}, 0.5})});
}

TEST(ProtocolMessages, RefusesOversizedTextBeforeParsing) {
    std::string big(kMaxRequestBytes + 1, '[');  // would also be far too deep
    expect_refused(big, ErrorCode::too_large, "16385 bytes", ParseLimits{});
    std::string aim = encode(Aim{std::nullopt, {1, 2}, 1});
    expect_refused(aim, ErrorCode::too_large, "limit of 10", ParseLimits{10, kMaxDepth});
    EXPECT_TRUE(std::holds_alternative<Message>(parse_message(aim, ParseLimits{aim.size(), kMaxDepth})));
}

TEST(ProtocolMessages, RefusesWhatIsNotAJsonObject) {
    expect_refused("", ErrorCode::bad_request, "not valid JSON");
    expect_refused("{\"type\": ", ErrorCode::bad_request, "not valid JSON");
    expect_refused("{\"type\":\"seeking\",\"v\":1} trailing", ErrorCode::bad_request, "not valid JSON");
    expect_refused("{\"type\":\"seeking\",\"v\":NaN}", ErrorCode::bad_request, "not valid JSON");
    expect_refused("[1, 2]", ErrorCode::bad_request, "must be a JSON object");
    expect_refused("\"seeking\"", ErrorCode::bad_request, "must be a JSON object");
    expect_refused("null", ErrorCode::bad_request, "must be a JSON object");
}

TEST(ProtocolMessages, RefusesInvalidUtf8) {
    for (std::string bad : {"\xff", "\xc0\xaf", "\xe0\x80\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xc3"}) {
        expect_refused("{\"type\":\"hello\",\"v\":1,\"token\":\"t\",\"client\":\"a" + bad + "b\"}",
                       ErrorCode::bad_request, "not valid UTF-8");
    }
    // An escaped lone surrogate is valid UTF-8 text but not valid JSON.
    expect_refused(R"({"type":"hello","v":1,"token":"t","client":"\ud800"})", ErrorCode::bad_request,
                   "not valid JSON");
    // Valid multi-byte text passes.
    EXPECT_TRUE(std::holds_alternative<Message>(
        parse_message("{\"type\":\"hello\",\"v\":1,\"token\":\"t\",\"client\":\"\xf0\x9f\x93\xb1 \xc3\xa9\"}")));
}

TEST(ProtocolMessages, RefusesDeepNesting) {
    auto nested = [](int levels) {  // the message object itself is level 1
        std::string extra;
        for (int i = 1; i < levels; ++i) extra += "[";
        for (int i = 1; i < levels; ++i) extra += "]";
        return "{\"type\":\"seeking\",\"v\":1,\"x\":" + (levels > 1 ? extra : std::string("0")) + "}";
    };
    EXPECT_TRUE(std::holds_alternative<Message>(parse_message(nested(16))));
    expect_refused(nested(17), ErrorCode::bad_request, "nested deeper than 16 levels");
    std::string objects = "{\"type\":\"seeking\",\"v\":1";
    for (int i = 0; i < 16; ++i) objects += ",\"a\":{\"b\":1";
    for (int i = 0; i < 16; ++i) objects += "}";
    expect_refused(objects + "}", ErrorCode::bad_request, "nested deeper");
    // Far deeper, within the size limit: refused without trouble.
    std::string deep = std::string(kMaxRequestBytes / 2, '[') + std::string(kMaxRequestBytes / 2, ']');
    expect_refused(deep, ErrorCode::bad_request, "nested deeper", ParseLimits{});
    expect_refused(std::string(100000, '['), ErrorCode::bad_request, "nested deeper", ParseLimits{1 << 20, kMaxDepth});
}

TEST(ProtocolMessages, RefusesBadTypeAndVersion) {
    expect_refused(R"({"v":1})", ErrorCode::bad_request, "missing \"type\"");
    expect_refused(R"({"type":7,"v":1})", ErrorCode::bad_request, "\"type\" must be a string");
    expect_refused(R"({"type":"teleport","v":1})", ErrorCode::bad_request, "unknown type \"teleport\"");
    expect_refused(R"({"type":"seeking"})", ErrorCode::bad_request, "missing \"v\"");
    expect_refused(R"({"type":"seeking","v":"1"})", ErrorCode::bad_request, "\"v\" must be an integer");
    expect_refused(R"({"type":"seeking","v":1.0})", ErrorCode::bad_request, "\"v\" must be an integer");
    expect_refused(R"({"type":"seeking","v":2})", ErrorCode::unsupported_version, "version 2 is not supported");
    expect_refused(R"({"type":"seeking","v":0})", ErrorCode::unsupported_version, "version 0");
    expect_refused(R"({"type":"seeking","v":18446744073709551615})", ErrorCode::bad_request, "\"v\"");
    // A newer version is reported as such even with a type this side does not know.
    expect_refused(R"({"type":"teleport","v":2})", ErrorCode::unsupported_version, "speaks version 1");
}

TEST(ProtocolMessages, RefusesMissingAndMistypedMembers) {
    const std::string aim = R"({"type":"aim","v":1,"point":[1,2],"confidence":0.5})";
    expect_refused(replaced(aim, R"("point":[1,2],)", ""), ErrorCode::bad_request, "missing \"point\"");
    expect_refused(replaced(aim, "[1,2]", "\"1,2\""), ErrorCode::bad_request, "\"point\" must be [u, v]");
    expect_refused(replaced(aim, "[1,2]", "[1,2,3]"), ErrorCode::bad_request, "\"point\" must be [u, v]");
    expect_refused(replaced(aim, "[1,2]", "[1,true]"), ErrorCode::bad_request, "\"point\" must be [u, v]");
    expect_refused(replaced(aim, ",\"confidence\":0.5", ""), ErrorCode::bad_request, "missing \"confidence\"");
    expect_refused(replaced(aim, "0.5", "\"high\""), ErrorCode::bad_request, "\"confidence\" must be a number 0..1");
    // The view's outline requesters sent before is no member any more: ignored, whatever its form.
    EXPECT_EQ(parsed(parse_message(replaced(aim, "}", R"(,"quad":[[0,0],[1,0],[1,1],[0,"x"]]})"))),
              Message{(Aim{std::nullopt, {1, 2}, 0.5})});

    expect_refused(R"({"type":"hello","v":1,"client":"c"})", ErrorCode::bad_request, "missing \"token\"");
    expect_refused(R"({"type":"hello","v":1,"token":5,"client":"c"})", ErrorCode::bad_request,
                   "\"token\" must be a string");
    expect_refused(R"({"type":"hello","v":1,"token":"","client":"c"})", ErrorCode::bad_request,
                   "\"token\" must be 1 to 128 bytes long");
    expect_refused(R"({"type":"target","v":1,"point":[1,2],"kind":"book","title":""})", ErrorCode::bad_request,
                   "\"kind\" must be");
    expect_refused(R"({"type":"error","v":1,"code":"oops","message":""})", ErrorCode::bad_request,
                   "\"code\" is not an error code");
    expect_refused(R"({"type":"error","v":1,"code":"internal"})", ErrorCode::bad_request, "missing \"message\"");
}

TEST(ProtocolMessages, RefusesNumbersOutOfRange) {
    const std::string aim = R"({"type":"aim","v":1,"point":[1,2],"confidence":0.5})";
    expect_refused(replaced(aim, "[1,2]", "[1e6,-1000000.5]"), ErrorCode::bad_request, "within +-1e6");
    // nlohmann refuses numbers that overflow a double, so no infinity gets through.
    expect_refused(replaced(aim, "[1,2]", "[1e400,2]"), ErrorCode::bad_request, "not valid JSON");
    expect_refused(replaced(aim, "0.5", "1.5"), ErrorCode::bad_request, "\"confidence\" must be a number 0..1, not 1.5");
    expect_refused(replaced(aim, "0.5", "-1e-9"), ErrorCode::bad_request, "\"confidence\"");
    expect_refused(replaced(aim, "0.5", "-1e999"), ErrorCode::bad_request, "not valid JSON");

    const std::string file = encode(sample_file());
    expect_refused(replaced(file, "\"size\":123456", "\"size\":-1"), ErrorCode::bad_request,
                   "\"size\" must be an integer 0..9007199254740991, not -1");
    expect_refused(replaced(file, "\"size\":123456", "\"size\":1.5"), ErrorCode::bad_request, "\"size\" must be an integer");
    expect_refused(replaced(file, "\"size\":123456", "\"size\":9007199254740992"), ErrorCode::bad_request, "\"size\"");

    const std::string welcome = encode(sample_welcome());
    expect_refused(replaced(welcome, "\"opacity_max\":0.4", "\"opacity_max\":0.05"), ErrorCode::bad_request,
                   "\"overlay.opacity_min\" is above \"overlay.opacity_max\"");
    expect_refused(replaced(welcome, "\"period_s\":1.5", "\"period_s\":0.1"), ErrorCode::bad_request,
                   "\"overlay.period_s\" must be 0 or at least 0.5");
    expect_refused(replaced(welcome, "\"max_message_bytes\":16384", "\"max_message_bytes\":-5"),
                   ErrorCode::bad_request, "\"limits.max_message_bytes\" must be an integer");
    expect_refused(replaced(welcome, "\"aims_per_s\":10.0", "\"aims_per_s\":0"), ErrorCode::bad_request,
                   "\"limits.aims_per_s\"");
    expect_refused(replaced(welcome, "[32.0,0.0,64.0,36.0]", "[32.0,0.0,65.0,36.0]"), ErrorCode::bad_request,
                   "\"field.screens[1].region\" must be [u0, v0, u1, v1] with 0 <= u0 < u1 <= 64");
    expect_refused(replaced(welcome, "[32.0,0.0,64.0,36.0]", "[31.0,0.0,64.0,36.0]"), ErrorCode::bad_request,
                   "the regions of screens 0 and 1 overlap");
    expect_refused(replaced(welcome, "[1920,2160]", "[0,2160]"), ErrorCode::bad_request,
                   "\"field.screens[0].pixels\" must be [width, height]");
    expect_refused(replaced(welcome, "\"window\":4", "\"window\":5"), ErrorCode::bad_request,
                   "\"field.definition\": window must be 3 or 4");
    expect_refused(replaced(welcome, "\"rows\"", "\"lines\""), ErrorCode::bad_request,
                   "\"field.definition\": missing \"rows\"");
    expect_refused(replaced(welcome, "\"waveform\":\"sine\"", "\"waveform\":\"square\""), ErrorCode::bad_request,
                   "\"overlay.waveform\" must be \"sine\" or \"triangle\"");
    expect_refused(replaced(welcome, "\"name\":\"desk-1\"", "\"name\":\"\""), ErrorCode::bad_request,
                   "\"provider.name\" must be 1 to 128 bytes long");
}

TEST(ProtocolMessages, RefusesStringsAboveTheirCaps) {
    auto target = [](std::size_t title_bytes) {
        return R"({"type":"target","v":1,"point":[1,2],"kind":"none","title":")" + std::string(title_bytes, 't') + "\"}";
    };
    EXPECT_TRUE(std::holds_alternative<Message>(parse_message(target(kMaxTitleBytes))));
    expect_refused(target(kMaxTitleBytes + 1), ErrorCode::bad_request, "\"title\" must be at most 512 bytes long, not 513");
    expect_refused(R"({"type":"hello","v":1,"client":"","token":")" + std::string(129, 'k') + "\"}",
                   ErrorCode::bad_request, "\"token\" must be 1 to 128 bytes long, not 129");
    expect_refused(R"({"type":"seeking","v":1,"id":")" + std::string(65, 'i') + "\"}", ErrorCode::bad_request,
                   "\"id\" must be 1 to 64 bytes long, not 65");
    expect_refused(R"({"type":"seeking","v":1,"id":""})", ErrorCode::bad_request, "\"id\" must be 1 to 64");
    expect_refused(R"({"type":"seeking","v":1,"id":1.5})", ErrorCode::bad_request, "\"id\" must be a string or an integer");
    expect_refused(R"({"type":"seeking","v":1,"id":9007199254740992})", ErrorCode::bad_request, "\"id\"");
    expect_refused(R"({"type":"error","v":1,"code":"internal","message":")" + std::string(1025, 'm') + "\"}",
                   ErrorCode::bad_request, "\"message\" must be at most 1024 bytes");
}

TEST(ProtocolMessages, RefusesUnsafeContent) {
    const std::string file = encode(sample_file());
    expect_refused(replaced(file, ",\"download\":\"/dl/Zm9vYmFyYmF6\"", ""), ErrorCode::bad_request,
                   "a file content needs \"download\"");
    expect_refused(replaced(file, ",\"mime\":\"application/pdf\"", ""), ErrorCode::bad_request,
                   "a file content needs \"mime\"");
    expect_refused(replaced(file, "\"name\":\"report.pdf\"", "\"name\":\"../../.bashrc\""), ErrorCode::bad_request,
                   "\"name\" must be a file name");
    expect_refused(replaced(file, "\"name\":\"report.pdf\"", "\"name\":\"..\""), ErrorCode::bad_request,
                   "\"name\" must be a file name");
    expect_refused(replaced(file, "\"name\":\"report.pdf\"", "\"name\":\"a\\\\b\""), ErrorCode::bad_request,
                   "\"name\" must be a file name");
    expect_refused(replaced(file, "\"name\":\"report.pdf\"", "\"name\":\"a\\nb\""), ErrorCode::bad_request,
                   "\"name\" must be a file name");
    expect_refused(replaced(file, "/dl/Zm9vYmFyYmF6", "//evil.example/x"), ErrorCode::bad_request,
                   "\"download\" must be a path");
    expect_refused(replaced(file, "/dl/Zm9vYmFyYmF6", "/dl/x@evil.example"), ErrorCode::bad_request,
                   "\"download\" must be a path");
    expect_refused(replaced(file, "/dl/Zm9vYmFyYmF6", "https://evil.example/x"), ErrorCode::bad_request,
                   "\"download\" must be a path");
    expect_refused(replaced(file, std::string(64, 'a'), std::string(64, 'A')), ErrorCode::bad_request,
                   "\"sha256\" must be 64 lowercase hex digits");
    expect_refused(replaced(file, std::string(64, 'a'), std::string(63, 'a')), ErrorCode::bad_request,
                   "\"sha256\" must be 64 bytes long, not 63");
    expect_refused(replaced(file, "application/pdf", "pdf"), ErrorCode::bad_request, "\"mime\" must be a media type");

    const std::string url = R"({"type":"content","v":1,"id":1,"kind":"url","title":"","url":"https://example.org/"})";
    EXPECT_TRUE(std::holds_alternative<Message>(parse_message(url)));
    EXPECT_TRUE(std::holds_alternative<Message>(parse_message(replaced(url, "https:", "HTTP:"))));
    expect_refused(replaced(url, "https://example.org/", "javascript:alert(1)"), ErrorCode::bad_request,
                   "\"url\" must be an http: or https: URL");
    expect_refused(replaced(url, "https://example.org/", "https://exa mple.org/"), ErrorCode::bad_request, "\"url\"");
    expect_refused(replaced(url, "https://example.org/", "https://"), ErrorCode::bad_request, "\"url\"");
    expect_refused(replaced(url, ",\"url\":\"https://example.org/\"", ""), ErrorCode::bad_request,
                   "a url content needs \"url\"");
}

TEST(ProtocolMessages, ErrorsEchoTheIdWhenItCanBeRead) {
    ProtocolError e = refused(R"({"type":"grab","v":1,"id":"g1","point":"here"})");
    EXPECT_EQ(e.code, ErrorCode::bad_request);
    EXPECT_EQ(e.id, std::optional<RequestId>(std::string("g1")));
    e = refused(R"({"type":"grab","v":1,"id":77})");
    EXPECT_EQ(e.id, std::optional<RequestId>(std::int64_t{77}));
    EXPECT_NE(e.message.find("missing \"point\""), std::string::npos);
    e = refused(R"({"type":"grab","v":3,"id":"g2","point":[1,2]})");
    EXPECT_EQ(e.code, ErrorCode::unsupported_version);
    EXPECT_EQ(e.id, std::optional<RequestId>(std::string("g2")));
    e = refused(R"({"type":"nope","v":1,"id":"g3"})");
    EXPECT_EQ(e.id, std::optional<RequestId>(std::string("g3")));

    // No id, or one that is itself malformed: nothing to echo.
    e = refused(R"({"type":"grab","v":1,"point":[1,2]})");
    EXPECT_NE(e.message.find("a grab needs an \"id\""), std::string::npos) << e.message;
    EXPECT_FALSE(e.id);
    EXPECT_FALSE(refused(R"({"type":"grab","v":1,"id":[1],"point":[1,2]})").id);
    EXPECT_FALSE(refused(R"({"type":"grab","v":1,"id":"g1","point":)").id);  // not JSON at all

    // The error message that answers it carries the id back.
    Error reply = to_error(refused(R"({"type":"grab","v":1,"id":"g1","point":[1e9,0]})"));
    EXPECT_EQ(reply.id, std::optional<RequestId>(std::string("g1")));
    Message back = parsed(parse_message(encode(reply)));
    EXPECT_EQ(std::get<Error>(back).id, reply.id);
    EXPECT_EQ(std::get<Error>(back).code, ErrorCode::bad_request);
}

TEST(ProtocolMessages, EncodeClipsDisplayTextAndRefusesTheRest) {
    Target t{std::nullopt, {1, 2}, ContentKind::url, ""};
    // 600 bytes of two-byte characters: cut at a character boundary within 512 bytes.
    for (int i = 0; i < 300; ++i) t.title += "\xc3\xa9";
    Target back = std::get<Target>(parsed(parse_message(encode(t))));
    EXPECT_EQ(back.title.size(), 512u);
    EXPECT_TRUE(is_valid_utf8(back.title));
    t.title = "bad \xff byte";
    EXPECT_EQ(std::get<Target>(parsed(parse_message(encode(t)))).title, "bad \xef\xbf\xbd byte");

    EXPECT_THROW(encode(Aim{std::nullopt, {std::nan(""), 0}, 1}), std::invalid_argument);
    EXPECT_THROW(encode(Aim{std::nullopt, {0, 0}, 2}), std::invalid_argument);
    EXPECT_THROW(encode(Hello{std::nullopt, "", "c"}), std::invalid_argument);
    Content c = sample_file();
    c.download.reset();
    EXPECT_THROW(encode(c), std::invalid_argument);
    c = sample_file();
    c.url = "file:///etc/passwd";
    try {
        encode(c);
        ADD_FAILURE() << "encoded a file: URL";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("cannot encode the content message: \"url\""), std::string::npos) << e.what();
    }
    Welcome w = sample_welcome();
    w.field.definition.window = 7;
    EXPECT_THROW(encode(w), std::invalid_argument);
    w = sample_welcome();
    w.field.screens.clear();
    EXPECT_THROW(encode(w), std::invalid_argument);
}

TEST(ProtocolMessages, TryEncodeReportsWithoutThrowing) {
    std::string problem;
    EXPECT_EQ(try_encode(Seeking{}, &problem), std::optional<std::string>(R"({"type":"seeking","v":1})"));
    EXPECT_EQ(problem, "");
    EXPECT_FALSE(try_encode(Aim{std::nullopt, {0, std::nan("")}, 1}, &problem));
    EXPECT_NE(problem.find("cannot encode the aim message: \"point\""), std::string::npos) << problem;
    Welcome w = sample_welcome();
    w.field.definition.modules.pop_back();
    EXPECT_FALSE(try_encode(w, &problem));
    EXPECT_NE(problem.find("\"field.definition\": module count"), std::string::npos) << problem;
    EXPECT_FALSE(try_encode(w));
}

TEST(ProtocolMessages, SafeFileNamesAreAccepted) {
    EXPECT_EQ(safe_file_name("report.pdf"), "report.pdf");
    EXPECT_EQ(safe_file_name("a/b\\c\nd"), "a_b_c_d");
    EXPECT_EQ(safe_file_name(".."), "file");
    EXPECT_EQ(safe_file_name(""), "file");
    EXPECT_EQ(safe_file_name(std::string(300, 'x')).size(), kMaxFileNameBytes);
    for (std::string name : {"..", "a/b", "\x01", "\xff\xfe", "ok.txt"}) {
        Content c = sample_file();
        c.name = safe_file_name(name);
        EXPECT_NO_THROW(encode(c)) << name;
    }
}

// Whatever arrives, parsing returns a message or an error, and a message it
// accepts encodes to a text that parses back to the same message.
void check_any(const std::string& text) {
    ParseResult r = parse_message(text, kRequesterLimits);
    if (const auto* e = std::get_if<ProtocolError>(&r)) {
        ASSERT_FALSE(e->message.empty());
        ASSERT_TRUE(error_code_from_string(to_string(e->code)));
        ASSERT_NO_THROW(encode(to_error(*e)));
        return;
    }
    const Message& m = std::get<Message>(r);
    std::string again;
    ASSERT_NO_THROW(again = encode(m)) << text;
    ASSERT_EQ(parsed(parse_message(again, kRequesterLimits)), m) << text;
}

TEST(ProtocolMessages, RandomBytesNeverCrashTheParser) {
    std::mt19937 rng(20240601);
    const std::string alphabet = "{}[]\":,0123456789.-+eEtruefalsn \\u\xc3\xa9\xff";
    for (int i = 0; i < 10000; ++i) {
        std::size_t length = rng() % 200;
        std::string text(length, '\0');
        bool json_like = i % 2 == 0;
        for (auto& c : text)
            c = json_like ? alphabet[rng() % alphabet.size()] : static_cast<char>(rng() & 0xff);
        check_any(text);
        if (HasFatalFailure()) return;
    }
}

TEST(ProtocolMessages, MutatedMessagesNeverCrashTheParser) {
    std::mt19937 rng(7);
    std::vector<std::string> valid;
    for (const Message& m : samples())
        if (!std::holds_alternative<Welcome>(m)) valid.push_back(encode(m));
    std::string welcome = encode(sample_welcome());
    const std::vector<std::string> splices = {"null", "-1", "1e400", "\"\"", "[]", "{}", "\"v\":2", "\"id\":",
                                              "[[[[", "\xff", "\\u0000", "true", "9007199254740993", ","};
    int accepted = 0;
    for (int i = 0; i < 10000; ++i) {
        std::string text = i % 50 == 0 ? welcome : valid[rng() % valid.size()];
        int edits = 1 + static_cast<int>(rng() % 4);
        for (int k = 0; k < edits && !text.empty(); ++k) {
            std::size_t at = rng() % text.size();
            switch (rng() % 5) {
                case 0: text[at] = static_cast<char>(rng() & 0xff); break;
                case 1: text.erase(at, 1 + rng() % 8); break;
                case 2: text.insert(at, splices[rng() % splices.size()]); break;
                case 3: text.insert(at, text.substr(rng() % text.size(), rng() % 16)); break;
                default: text[at] ^= static_cast<char>(1u << (rng() % 8)); break;
            }
        }
        check_any(text);
        if (HasFatalFailure()) return;
        if (std::holds_alternative<Message>(parse_message(text, kRequesterLimits))) ++accepted;
    }
    // Some mutations land where they change nothing that matters (a digit of a
    // number, a character of a title); most are refused.
    EXPECT_GT(accepted, 100);
    EXPECT_LT(accepted, 9000);
}

// The welcome's overlay is the wire's own type: its waveform names and its
// limits stand without the overlay's presets.
TEST(ProtocolMessages, TheOverlaysWaveformIsTheWiresOwn) {
    EXPECT_STREQ(to_string(PulseWaveform::sine), "sine");
    EXPECT_STREQ(to_string(PulseWaveform::triangle), "triangle");
    EXPECT_EQ(pulse_waveform_from_string("triangle"), PulseWaveform::triangle);
    EXPECT_FALSE(pulse_waveform_from_string("square").has_value());
    Welcome w = sample_welcome();
    w.overlay.waveform = PulseWaveform::triangle;
    const auto back = std::get<Welcome>(parsed(parse_message(encode(w))));
    EXPECT_EQ(back.overlay, w.overlay);
}

}  // namespace
