// The provider's HTTP request path (provider/net/http_connection.cpp) without its
// socket: a connection's bytes parsed by Beast as HttpConnection parses them (the
// header first, under its 8 KiB limit; the framing check; the body under its
// 16 KiB limit, in a buffer of at most both), then what a complete request
// reaches without a socket: the HTTPS transport's sessions (hello, message,
// events, close) and through them the Service, the one-time links and the
// web client's files. Kept-alive requests follow one another on the same
// bytes. The first input byte says how many bytes arrive at a time, as TLS
// records cut a request anywhere.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <boost/asio/buffer.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <nlohmann/json.hpp>

#include "provider/board/board.hpp"
#include "provider/content/board_resolver.hpp"
#include "provider/content/download_table.hpp"
#include "provider/content/resume_range.hpp"
#include "provider/net/api_sessions.hpp"
#include "provider/net/http_framing.hpp"
#include "provider/put/put_decision.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"

namespace beast = boost::beast;
namespace http = beast::http;
namespace provider = umf::provider;

namespace {

// As HttpConnection has them.
constexpr std::size_t kMaxRequestHeaderBytes = 8 * 1024;
constexpr std::size_t kMaxRequestBodyBytes = 16 * 1024;
constexpr int kMaxRequestsPerInput = 8;
constexpr const char* kToken = "fuzz-token-0123456789abcdef";

// Every put is dismissed at once: the put's checks and answers run, and no
// file is ever written.
class Dismiss : public provider::PutDecider {
public:
    void ask(const provider::PutOffer&, std::function<void(provider::PutReply)> answer) override {
        answer(provider::PutReply{provider::PutAnswer::dismiss, false});
    }
    void withdraw(std::uint64_t) override {}
};

// A service as `serve` makes one, with a board of a link and a file, and the
// HTTPS transport's table. The io_context never runs: the table's expiry
// timer only waits.
struct Provider {
    boost::asio::io_context io;
    std::shared_ptr<provider::Service> service;
    std::shared_ptr<provider::ApiSessions> sessions;
    std::string session;  // a welcomed session's id, for /api/session/... ("" once ended)

    Provider() {
        provider::Board board;
        board.items.push_back({"Project site", std::nullopt, std::string("https://example.org/"), std::nullopt,
                               std::nullopt});
        board.items.push_back({"Fields", std::filesystem::path(UMF_DATA_DIR) / "fields" / "README.md", std::nullopt,
                               std::nullopt, std::nullopt});
        auto resolver = std::make_shared<provider::BoardResolver>(
            board, std::vector<provider::PixelRect>{{0, 0, 960, 1080}, {960, 0, 960, 1080}});
        provider::ServiceConfig config = provider::default_service_config();
        config.put_decider = std::make_shared<Dismiss>();
        config.puts.folder = std::filesystem::temp_directory_path();
        service = std::make_shared<provider::Service>(
            std::move(config), kToken, std::vector<std::shared_ptr<const provider::Resolver>>{resolver});
        sessions = provider::ApiSessions::create(io.get_executor(), service);
    }

    static std::string session_of(const provider::ApiSessions::Reply& reply) {
        if (reply.ended) return {};
        const auto body = nlohmann::json::parse(reply.body, nullptr, false);
        if (!body.is_object() || !body.contains("session") || !body["session"].is_string()) return {};
        return body["session"].get<std::string>();
    }

    const std::string& welcomed_session() {
        if (session.empty())
            session = session_of(sessions->hello(std::string(R"({"type":"hello","v":1,"token":")") + kToken +
                                                     R"(","client":"fuzz"})",
                                                 "fixture"));
        return session;
    }
};

Provider& the_provider() {
    static Provider* p = new Provider;  // lives to the end: libFuzzer exits without unwinding
    return *p;
}

// The connection's bytes, arriving `chunk` at a time into a buffer of at
// most `max_buffer` bytes (Session's flat_buffer limit).
struct Wire {
    std::string_view unread;
    std::size_t chunk;
    std::string buffered;

    bool arrive(std::size_t max_buffer) {
        const std::size_t room = max_buffer > buffered.size() ? max_buffer - buffered.size() : 0;
        const std::size_t n = std::min({chunk, unread.size(), room});
        if (n == 0) return false;
        buffered.append(unread.substr(0, n));
        unread.remove_prefix(n);
        return true;
    }
};

// What http::read_header and http::read do: put what is buffered, read more
// when the parser needs it, put_eof when the peer is gone.
template <class Parser>
beast::error_code read(Parser& parser, Wire& wire, std::size_t max_buffer, bool header_only) {
    for (;;) {
        if (header_only ? parser.is_header_done() : parser.is_done()) return {};
        if (!wire.buffered.empty()) {
            beast::error_code ec;
            const std::size_t used = parser.put(boost::asio::buffer(wire.buffered), ec);
            wire.buffered.erase(0, used);
            if (ec && ec != http::error::need_more) return ec;
            if (!ec && used > 0) continue;
        }
        if (wire.unread.empty()) {
            if (!parser.got_some()) return http::error::end_of_stream;
            beast::error_code ec;
            parser.put_eof(ec);
            return ec ? ec : beast::error_code(http::error::partial_message);
        }
        if (!wire.arrive(max_buffer)) return http::error::buffer_overflow;
    }
}

// HttpConnection::serve_api's routing, calling what it calls.
void serve_api(Provider& p, const http::request<http::string_body>& req) {
    beast::string_view path = req.target();
    path = path.substr(0, path.find('?'));
    if (path == "/api/hello") {
        const std::string welcomed = Provider::session_of(p.sessions->hello(req.body(), "fuzz"));
        if (!welcomed.empty()) p.sessions->close(welcomed);  // the table stays as it was
        return;
    }
    static constexpr beast::string_view kSessionPrefix = "/api/session/";
    if (!path.starts_with(kSessionPrefix)) return;
    const beast::string_view rest = path.substr(kSessionPrefix.size());
    const auto slash = rest.find('/');
    const beast::string_view id = rest.substr(0, slash);
    const beast::string_view tail = slash == beast::string_view::npos ? beast::string_view() : rest.substr(slash);
    if (id.empty()) return;
    // An id of the right length is taken as sent (an unknown session); any
    // other stands for the welcomed one, which no input could guess.
    const std::string session = id.size() == provider::kApiSessionIdChars ? std::string(id) : p.welcomed_session();
    if (session.empty()) return;
    const bool fixture = session == p.session;
    std::optional<provider::ApiSessions::Reply> reply;
    if (tail.empty()) {
        reply = p.sessions->message(session, req.body());
    } else if (tail == "/close") {
        reply = p.sessions->close(session);
    } else if (tail == "/events") {
        auto start = p.sessions->begin_poll(session, [](provider::ApiSessions::Reply) {});
        if (start.now) reply = std::move(start.now);
        else p.sessions->cancel_poll(start.ticket);  // the client left at once
    }
    if (fixture && reply && reply->ended) p.session.clear();
}

// The routes' socket-free part (net/http_connection.cpp, service/service_server.cpp).
void serve(Provider& p, const http::request<http::string_body>& req) {
    const beast::string_view target = req.target();
    const std::string_view path(target.data(), target.size());
    if (beast::websocket::is_upgrade(req)) return;  // the handshake needs the stream
    if (target.starts_with(provider::kApiPrefix)) {
        serve_api(p, req);
        return;
    }
    if (req.method() != http::verb::get && req.method() != http::verb::head) return;
    if (target.starts_with(provider::kDownloadPrefix)) {
        if (auto checkout = p.service->downloads().begin(path)) p.service->downloads().end(*checkout, true);
        // The part a resume asks for, against a file of a size the request
        // picks itself (its length): never past the end.
        const auto field = [&](http::field f) {
            const beast::string_view v = req[f];
            return std::string_view(v.data(), v.size());
        };
        const std::uint64_t size = req.body().size();
        const auto range = provider::resume_range(field(http::field::range), field(http::field::if_range),
                                                  provider::download_etag("ab"), size);
        if (range.kind == provider::ResumeRange::Kind::rest && range.offset >= size) __builtin_trap();
        return;
    }
    (void)p.service->site().find(path);
}

// One request as HttpConnection::read_request, on_header and on_request take it;
// whether the connection goes on to another.
bool one_request(Provider& p, Wire& wire) {
    http::request_parser<http::empty_body> header;
    header.header_limit(kMaxRequestHeaderBytes);
    header.body_limit(std::numeric_limits<std::uint64_t>::max());
    if (read(header, wire, kMaxRequestHeaderBytes + kMaxRequestBodyBytes, true)) return false;
    if (provider::ambiguous_framing(header.get().version(), header.get())) return false;
    const beast::string_view target = header.get().target();
    if (target.starts_with(provider::kUploadPrefix)) {
        // The link is used up whatever follows; no input can name a live one.
        if (auto checkout = p.service->puts().begin_upload(std::string_view(target.data(), target.size())))
            p.service->puts().end_upload(*checkout, provider::UploadEnd::failed);
        return false;
    }
    if (header.get().method() == http::verb::post && target.substr(0, target.find('?')) == "/share") return false;
    if (const auto length = header.content_length(); length && *length > kMaxRequestBodyBytes) return false;
    http::request_parser<http::string_body> request(std::move(header));
    request.body_limit(kMaxRequestBodyBytes);
    request.eager(true);
    if (read(request, wire, kMaxRequestHeaderBytes + kMaxRequestBodyBytes, false)) return false;
    const auto& req = request.get();
    serve(p, req);
    return req.keep_alive() && !beast::websocket::is_upgrade(req);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    // 0 stands for "everything at once".
    const std::size_t chunk = data[0] == 0 ? std::numeric_limits<std::size_t>::max() : data[0];
    Wire wire{std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1), chunk, {}};
    Provider& p = the_provider();
    for (int i = 0; i < kMaxRequestsPerInput && one_request(p, wire); ++i) {
    }
    return 0;
}
