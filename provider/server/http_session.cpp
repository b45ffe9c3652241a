#include "server/http_session.hpp"

#include <boost/asio/post.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <algorithm>
#include <cstdio>
#include <cctype>
#include <chrono>
#include <limits>
#include <exception>
#include <stdexcept>

#include "content/download_table.hpp"
#include "content/verified_file_body.hpp"
#include "protocol/http_error_body.hpp"
#include "server/http_framing.hpp"
#include "server/lingering_close.hpp"
#include "server/listener.hpp"
#include "server/websocket_session.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;

namespace {

// A request's time to arrive, and an answer's to be written.
constexpr auto kHandshakeTimeout = std::chrono::seconds(30);
constexpr std::size_t kMaxRequestHeaderBytes = 8 * 1024;
// Bodies carry one message of the HTTPS transport (docs/PROTOCOL.md, "Limits").
constexpr std::size_t kMaxRequestBodyBytes = 16 * 1024;
// An upload's body goes to its file in chunks of this size.
constexpr std::size_t kUploadChunkBytes = 64 * 1024;
// The web client's share target (its manifest): a share is taken by the
// page's service worker; one that reaches the provider found none active.
constexpr const char* kSharePath = "/share";
constexpr const char* kShareUnavailable = "/?share=unavailable";

}  // namespace

HttpSession::HttpSession(TlsStream&& stream, beast::flat_buffer&& buffer, std::unique_ptr<SessionState> state,
                         std::shared_ptr<const Service> service, std::shared_ptr<SessionRegistry> registry,
                         std::shared_ptr<HttpSessions> http_sessions)
    : executor_(stream.get_executor()),
      stream_(std::move(stream)),
      service_(std::move(service)),
      registry_(std::move(registry)),
      http_sessions_(std::move(http_sessions)),
      buffer_(std::move(buffer)),
      state_(std::move(state)),
      timer_(executor_) {}

HttpSession::~HttpSession() {
    if (poll_pending_ && http_sessions_) http_sessions_->cancel_poll(poll_ticket_);
    if (upload_entry_) {
        // Torn down mid-upload without a handler to hear it (the server stopping).
        upload_sink_.reset();
        service_->puts().upload_failed(*upload_entry_, protocol::ErrorCode::interrupted,
                                       "the upload was cut off: the provider closed the connection");
    }
    if (state_) service_->session_ended(*state_);
    if (registry_) registry_->remove(this);
}

void HttpSession::run() { read_request(); }

void HttpSession::read_request() {
    // Also the idle timeout of a kept-alive connection.
    beast::get_lowest_layer(stream_).expires_after(kHandshakeTimeout);
    request_.reset();
    header_.emplace();
    header_->header_limit(kMaxRequestHeaderBytes);
    // The body's limit depends on the path: an upload's is its put's size,
    // anything else's kMaxRequestBodyBytes (on_header). Not boost::none:
    // Beast 1.74 compares the length with the optional, and none is less
    // than every length.
    header_->body_limit(std::numeric_limits<std::uint64_t>::max());
    buffer_.max_size(kMaxRequestHeaderBytes + kMaxRequestBodyBytes);
    http::async_read_header(stream_, buffer_, *header_,
                            beast::bind_front_handler(&HttpSession::on_header, shared_from_this()));
}

void HttpSession::request_failed(beast::error_code ec) {
    // A request that is not HTTP or too large gets its status; a
    // connection gone or timed out, nothing.
    if (ec == http::error::header_limit || ec == http::error::buffer_overflow)
        answer_error(http::status::request_header_fields_too_large, false, protocol::ErrorCode::too_large,
                     "the request's header is larger than " + std::to_string(kMaxRequestHeaderBytes) + " bytes");
    else if (ec == http::error::body_limit)
        answer_error(http::status::payload_too_large, false, protocol::ErrorCode::too_large,
                     "the body is larger than " + std::to_string(kMaxRequestBodyBytes) + " bytes");
    else if (ec.category() == http::make_error_code(http::error::bad_method).category() &&
             ec != http::error::end_of_stream && ec != http::error::partial_message)
        answer_error(http::status::bad_request, false, protocol::ErrorCode::bad_request,
                     "a request that cannot be read: " + ec.message());
}

void HttpSession::on_header(beast::error_code ec, std::size_t) {
    if (closing_) return;
    if (ec) {
        request_failed(ec);
        return;
    }
    if (const auto why = ambiguous_framing(header_->get().version(), header_->get())) {
        // Never served, never read on: the connection ends with the answer.
        answer_error(http::status::bad_request, false, protocol::ErrorCode::bad_request, *why);
        return;
    }
    const beast::string_view target = header_->get().target();
    if (target.starts_with(kUploadPrefix)) {
        start_upload();
        return;
    }
    // Sent back to the page, which says to open it once first. The body (the
    // shared files) is not read: the connection closes after the answer.
    if (header_->get().method() == http::verb::post && target.substr(0, target.find('?')) == kSharePath) {
        auto res = std::make_shared<http::response<http::string_body>>(http::status::see_other, 11);
        res->set(http::field::server, "umf-provider");
        res->set(http::field::location, kShareUnavailable);
        res->set(http::field::cache_control, "no-store");
        res->set("Referrer-Policy", "no-referrer");
        res->keep_alive(false);
        res->prepare_payload();
        beast::get_lowest_layer(stream_).expires_after(kHandshakeTimeout);
        write_response(std::move(res));
        return;
    }
    // A declared length is checked here; a chunked body chunk by chunk.
    if (const auto length = header_->content_length(); length && *length > kMaxRequestBodyBytes) {
        request_failed(http::error::body_limit);
        return;
    }
    request_.emplace(std::move(*header_));
    header_.reset();
    request_->body_limit(kMaxRequestBodyBytes);
    if (request_->is_done()) {
        // No body: nothing more to read.
        net::post(executor_, [self = shared_from_this()] { self->on_request({}, 0); });
        return;
    }
    http::async_read(stream_, buffer_, *request_,
                     beast::bind_front_handler(&HttpSession::on_request, shared_from_this()));
}

void HttpSession::on_request(beast::error_code ec, std::size_t) {
    if (closing_) return;
    if (ec) {
        request_failed(ec);
        return;
    }
    buffer_.max_size(std::numeric_limits<std::size_t>::max());
    const auto& req = request_->get();
    if (!websocket::is_upgrade(req)) {
        serve_http(req);
        return;
    }
    const beast::string_view target = req.target();
    if (target.substr(0, target.find('?')) != kWebSocketPath) {
        answer_error(http::status::not_found, false, protocol::ErrorCode::not_found,
                     std::string("the WebSocket is at ") + kWebSocketPath);
        return;
    }
    upgrade(req);
}

void HttpSession::upgrade(const http::request<http::string_body>& req) {
    auto ws = std::make_shared<WebSocketSession>(std::move(stream_), std::move(buffer_), std::move(state_), service_,
                                                 registry_);
    registry_->hand_over(this, ws.get(), ws);
    next_ = ws;
    ws->run(req);
}

namespace {

template <class Body>
void set_common_headers(http::response<Body>& res) {
    res.set(http::field::server, "umf-provider");
    res.set("X-Content-Type-Options", "nosniff");
    res.set("Referrer-Policy", "no-referrer");
}

// RFC 6266 / 8187: a plain ASCII fallback and the UTF-8 name percent-encoded.
std::string content_disposition(const std::string& name) {
    std::string ascii, encoded;
    static constexpr char kHex[] = "0123456789ABCDEF";
    for (unsigned char c : name) {
        ascii += (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') ? static_cast<char>(c) : '_';
        if (std::isalnum(c) || c == '.' || c == '-' || c == '_' || c == '~') {
            encoded += static_cast<char>(c);
        } else {
            encoded += '%';
            encoded += kHex[c >> 4];
            encoded += kHex[c & 15];
        }
    }
    return "attachment; filename=\"" + ascii + "\"; filename*=UTF-8''" + encoded;
}


// For the web client's files: a page that runs WebAssembly in a module worker
// and talks to its own origin over https: and wss:. 'self' covers wss: to the
// same host and port only in browsers that follow CSP Level 3 on this point,
// so the WebSocket's own origin is named as well, from the Host header the
// page was loaded with (when it is a plain host[:port]).
std::string content_security_policy(beast::string_view host) {
    std::string connect = "'self'";
    const bool plain_host = !host.empty() && host.size() <= 262 &&
                            std::all_of(host.begin(), host.end(), [](char c) {
                                return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ||
                                       c == ':' || c == '[' || c == ']';
                            });
    if (plain_host) connect += " wss://" + std::string(host);
    return "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self' blob:; connect-src " +
           connect +
           "; img-src 'self' blob: data:; media-src 'self' blob:; style-src 'self'; object-src 'none'; "
           "base-uri 'none'; frame-ancestors 'none'; form-action 'self'";
}

// A POST of the HTTPS transport must say its body is JSON: a page of another
// origin cannot send that without a CORS preflight, which is never answered.
bool is_json(beast::string_view content_type) {
    const auto end = content_type.find(';');
    beast::string_view type = content_type.substr(0, end);
    while (!type.empty() && (type.back() == ' ' || type.back() == '\t')) type.remove_suffix(1);
    while (!type.empty() && (type.front() == ' ' || type.front() == '\t')) type.remove_prefix(1);
    return beast::iequals(type, "application/json");
}

}  // namespace

void HttpSession::serve_api(const http::request<http::string_body>& req) {
    const bool keep_alive = req.keep_alive();
    beast::string_view path = req.target();
    path = path.substr(0, path.find('?'));
    enum class Call { none, hello, message, events, close } call = Call::none;
    beast::string_view id;
    static constexpr beast::string_view kSessionPrefix = "/api/session/";
    if (path == "/api/hello") {
        call = Call::hello;
    } else if (path.starts_with(kSessionPrefix)) {
        beast::string_view rest = path.substr(kSessionPrefix.size());
        const auto slash = rest.find('/');
        id = rest.substr(0, slash);
        const beast::string_view tail = slash == beast::string_view::npos ? beast::string_view() : rest.substr(slash);
        if (!id.empty()) {
            if (tail.empty())
                call = Call::message;
            else if (tail == "/events")
                call = Call::events;
            else if (tail == "/close")
                call = Call::close;
        }
    }
    if (call == Call::none) {
        answer_error(http::status::not_found, keep_alive, protocol::ErrorCode::not_found, "no such API path");
        return;
    }
    const http::verb method = call == Call::events ? http::verb::get : http::verb::post;
    if (req.method() != method) {
        answer_error(http::status::method_not_allowed, keep_alive, protocol::ErrorCode::bad_request,
                  std::string("this path takes ") + (method == http::verb::get ? "GET" : "POST") + " only",
                  method == http::verb::get ? "GET" : "POST");
        return;
    }
    if (method == http::verb::post && !is_json(req[http::field::content_type])) {
        answer_error(http::status::unsupported_media_type, keep_alive, protocol::ErrorCode::bad_request,
                  "the body must be sent as Content-Type: application/json");
        return;
    }
    const std::string_view session(id.data(), id.size());
    HttpSessions::Reply reply;
    switch (call) {
        case Call::hello:
            reply = http_sessions_->hello(req.body(), state_->peer);
            break;
        case Call::message:
            reply = http_sessions_->message(session, req.body());
            break;
        case Call::close:
            reply = http_sessions_->close(session);
            break;
        case Call::events:
            start_poll(session, keep_alive);
            return;
        case Call::none:
            return;
    }
    api_response(reply.status, keep_alive, std::move(reply.body));
}

void HttpSession::api_response(int status, bool keep_alive, std::string body, const char* allow) {
    auto res = std::make_shared<http::response<http::string_body>>(static_cast<http::status>(status), 11);
    set_common_headers(*res);
    res->set(http::field::content_type, "application/json");
    res->set(http::field::cache_control, "no-store");
    if (allow) res->set(http::field::allow, allow);
    res->keep_alive(keep_alive);
    res->body() = std::move(body);
    res->prepare_payload();
    write_response(std::move(res));
}

void HttpSession::answer_error(http::status status, bool keep_alive, const protocol::Error& error, const char* allow) {
    if (!keep_alive) {
        beast::get_lowest_layer(stream_).expires_after(kHandshakeTimeout);
        linger_after_response_ = true;
    }
    api_response(static_cast<int>(status), keep_alive, protocol::encode_error_body(error), allow);
}

void HttpSession::answer_error(http::status status, bool keep_alive, protocol::ErrorCode code, const std::string& message,
                           const char* allow) {
    answer_error(status, keep_alive, protocol::Error{std::nullopt, code, message}, allow);
}

void HttpSession::start_poll(std::string_view id, bool keep_alive) {
    const std::uint64_t poll = ++poll_serial_;
    // Called at most once, from any thread: the answer goes to this strand.
    auto waiter = [weak = weak_from_this(), executor = executor_, poll](HttpSessions::Reply reply) {
        net::post(executor, [weak, poll, reply = std::move(reply)]() mutable {
            if (auto self = weak.lock()) self->finish_poll(poll, std::move(reply));
        });
    };
    HttpSessions::PollStart start = http_sessions_->begin_poll(id, std::move(waiter));
    if (start.now) {
        api_response(start.now->status, keep_alive, std::move(start.now->body));
        return;
    }
    poll_pending_ = true;
    poll_ticket_ = start.ticket;
    poll_keep_alive_ = keep_alive;
    // The poll's own timer bounds it; the read below has no timeout.
    beast::get_lowest_layer(stream_).expires_never();
    arm_timer(std::chrono::duration_cast<std::chrono::milliseconds>(http_sessions_->options().poll_timeout),
              &HttpSession::on_poll_timer);
    watch();
}

void HttpSession::arm_timer(std::chrono::milliseconds after, void (HttpSession::*handler)(beast::error_code, std::uint64_t)) {
    const std::uint64_t serial = ++timer_serial_;
    timer_.expires_after(after);
    timer_.async_wait([self = shared_from_this(), handler, serial](beast::error_code ec) {
        ((*self).*handler)(ec, serial);
    });
}

void HttpSession::on_poll_timer(beast::error_code ec, std::uint64_t serial) {
    if (ec || serial != timer_serial_ || !poll_pending_) return;
    // Nothing came: answered with no messages, unless an answer is already
    // on its way to this strand.
    if (auto reply = http_sessions_->end_poll(poll_ticket_)) finish_poll(poll_serial_, std::move(*reply));
}

void HttpSession::on_idle_timer(beast::error_code ec, std::uint64_t serial) {
    if (ec || serial != timer_serial_ || !watching_) return;
    beast::get_lowest_layer(stream_).close();  // kept alive after a poll, but nothing came
}

void HttpSession::finish_poll(std::uint64_t poll, HttpSessions::Reply reply) {
    if (!poll_pending_ || poll != poll_serial_) return;
    poll_pending_ = false;
    ++timer_serial_;
    timer_.cancel();
    // The write gets the usual timeout (the watching read has none).
    beast::get_lowest_layer(stream_).expires_after(kHandshakeTimeout);
    api_response(reply.status, poll_keep_alive_ && !closing_, std::move(reply.body));
}

void HttpSession::watch() {
    // Reads whatever comes while the poll is open: nothing until the client
    // goes away (an error), or the start of its next request.
    if (buffer_.size() >= kMaxRequestHeaderBytes) return;  // a pipelining client waits for its answer
    watching_ = true;
    stream_.async_read_some(buffer_.prepare(2048),
                                     beast::bind_front_handler(&HttpSession::on_watch, shared_from_this()));
}

void HttpSession::on_watch(beast::error_code ec, std::size_t bytes) {
    watching_ = false;
    if (ec) {
        // Gone (or closed by a timeout or a shutdown): the poll is dropped,
        // its HTTP session stays until it expires or the client comes back.
        if (poll_pending_) {
            poll_pending_ = false;
            http_sessions_->cancel_poll(poll_ticket_);
        }
        ++timer_serial_;
        timer_.cancel();
        beast::get_lowest_layer(stream_).close();
        return;
    }
    buffer_.commit(bytes);
    if (poll_pending_) {
        watch();
        return;
    }
    if (resume_after_watch_) {
        // The poll is answered and written: on with the next request.
        resume_after_watch_ = false;
        ++timer_serial_;
        timer_.cancel();
        if (!closing_) read_request();
    }
    // Otherwise the answer is still being written; after_response goes on.
}


void HttpSession::start_upload() {
    http::request_parser<http::empty_body>& header = *header_;
    const auto& req = header.get();
    const beast::string_view target = req.target();
    if (req.method() != http::verb::put) {
        answer_error(http::status::method_not_allowed, false, protocol::ErrorCode::bad_request,
                  "an upload is a PUT", "PUT");
        return;
    }
    // The link is used up by this request, whatever follows.
    auto entry = service_->puts().take_upload(std::string_view(target.data(), target.size()));
    if (!entry) {
        answer_error(http::status::not_found, false, protocol::ErrorCode::not_found, "unknown, used or expired upload link");
        return;
    }
    upload_entry_ = std::move(*entry);
    const std::int64_t size = upload_entry_->size;
    const auto length = header.content_length();
    if (!length || header.chunked()) {
        const std::string why = "an upload needs a Content-Length of " + std::to_string(size);
        service_->puts().upload_failed(*upload_entry_, protocol::ErrorCode::interrupted, why);
        upload_entry_.reset();
        answer_error(http::status::length_required, false, protocol::ErrorCode::bad_request, why);
        return;
    }
    if (*length != static_cast<std::uint64_t>(size)) {
        const std::string why = "the upload's Content-Length is " + std::to_string(*length) + ", the put's size " +
                                std::to_string(size);
        service_->puts().upload_failed(*upload_entry_, protocol::ErrorCode::interrupted, why);
        upload_entry_.reset();
        answer_error(http::status::bad_request, false, protocol::ErrorCode::bad_request, why);
        return;
    }
    try {
        upload_sink_ = std::make_unique<UploadSink>(upload_entry_->folder, size, upload_entry_->sha256);
    } catch (const UploadError& e) {
        fail_upload(e.code(), e.what(), true);
        return;
    } catch (const std::exception& e) {
        fail_upload(protocol::ErrorCode::internal, e.what(), true);
        return;
    }
    const bool expect_continue = beast::iequals(req[http::field::expect], "100-continue");
    upload_.emplace(std::move(header));
    header_.reset();
    upload_->body_limit(static_cast<std::uint64_t>(size));
    buffer_.max_size(std::numeric_limits<std::size_t>::max());
    upload_chunk_.resize(kUploadChunkBytes);
    // A slow sender gets a minute plus a second per megabyte, as downloads.
    beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(60 + size / (1 << 20)));
    if (expect_continue) {
        auto res = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
        auto& r = *res;
        response_ = std::move(res);
        http::async_write(stream_, r, [self = shared_from_this()](beast::error_code ec, std::size_t) {
            self->response_.reset();
            if (ec) {
                self->fail_upload(protocol::ErrorCode::interrupted, "the upload broke off: " + ec.message(), false);
                return;
            }
            self->read_upload();
        });
        return;
    }
    read_upload();
}

void HttpSession::read_upload() {
    if (upload_->is_done()) {
        finish_upload();
        return;
    }
    auto& body = upload_->get().body();
    body.data = upload_chunk_.data();
    body.size = upload_chunk_.size();
    http::async_read(stream_, buffer_, *upload_,
                     beast::bind_front_handler(&HttpSession::on_upload, shared_from_this()));
}

void HttpSession::on_upload(beast::error_code ec, std::size_t) {
    if (!upload_ || !upload_sink_) return;
    if (ec == http::error::need_buffer) ec = {};
    const std::size_t got = upload_chunk_.size() - upload_->get().body().size;
    if (got > 0) {
        try {
            upload_sink_->write(upload_chunk_.data(), got);
        } catch (const UploadError& e) {
            fail_upload(e.code(), e.what(), !ec);
            return;
        }
    }
    if (ec) {
        fail_upload(protocol::ErrorCode::interrupted,
                    "the upload broke off after " + std::to_string(upload_sink_->received()) + " of " +
                        std::to_string(upload_entry_->size) + " bytes: " + ec.message(),
                    false);
        return;
    }
    if (closing_) {
        fail_upload(protocol::ErrorCode::interrupted, "the provider is stopping", false);
        return;
    }
    read_upload();
}

void HttpSession::finish_upload() {
    std::string stored;
    try {
        stored = upload_sink_->store(upload_entry_->name);
    } catch (const UploadError& e) {
        fail_upload(e.code(), e.what(), true);
        return;
    }
    upload_sink_.reset();
    const bool keep_alive = upload_->get().keep_alive();
    const UploadEntry entry = std::move(*upload_entry_);
    upload_entry_.reset();
    upload_.reset();
    upload_chunk_ = {};
    const protocol::Message done = service_->puts().upload_done(entry, stored);
    beast::get_lowest_layer(stream_).expires_after(kHandshakeTimeout);
    api_response(200, keep_alive && !closing_, encode_reply(done));
}

void HttpSession::fail_upload(protocol::ErrorCode code, const std::string& message, bool answer) {
    upload_sink_.reset();  // the temporary file goes with it
    upload_.reset();
    upload_chunk_ = {};
    if (!upload_entry_) return;
    const protocol::Error error = service_->puts().upload_failed(*upload_entry_, code, message);
    upload_entry_.reset();
    if (!answer) {
        beast::get_lowest_layer(stream_).close();
        return;
    }
    const auto status = code == protocol::ErrorCode::too_large  ? http::status::payload_too_large
                        : code == protocol::ErrorCode::internal ? http::status::internal_server_error
                                                                : http::status::bad_request;
    answer_error(status, false, error);
}

void HttpSession::serve_http(const http::request<http::string_body>& req) {
    const bool keep_alive = req.keep_alive();
    if (beast::string_view(req.target()).starts_with(kApiPrefix)) {
        serve_api(req);
        return;
    }
    if (req.method() != http::verb::get && req.method() != http::verb::head) {
        answer_error(http::status::method_not_allowed, keep_alive, protocol::ErrorCode::bad_request,
                   "only GET and HEAD are served here; POST only under /api/");
        return;
    }
    const beast::string_view target = req.target();
    if (target.starts_with(kDownloadPrefix)) {
        serve_download(req);
        return;
    }
    const auto file = service_->site().find(std::string_view(target.data(), target.size()));
    if (!file) {
        answer_error(http::status::not_found, keep_alive, protocol::ErrorCode::not_found, "no such page");
        return;
    }
    auto res = std::make_shared<http::response<http::string_body>>(http::status::ok, req.version());
    set_common_headers(*res);
    res->set(http::field::content_type, file->mime);
    res->set(http::field::cache_control, "no-cache");
    res->set("Content-Security-Policy", content_security_policy(req[http::field::host]));
    res->keep_alive(keep_alive);
    if (req.method() == http::verb::get) res->body() = *file->bytes;
    res->prepare_payload();
    if (req.method() == http::verb::head) res->content_length(file->bytes->size());
    write_response(std::move(res));
}

void HttpSession::serve_download(const http::request<http::string_body>& req) {
    const bool keep_alive = req.keep_alive();
    const beast::string_view target = req.target();
    // The link is used up by this request, whatever follows.
    auto entry = service_->downloads().take(std::string_view(target.data(), target.size()));
    if (!entry) {
        answer_error(http::status::not_found, keep_alive, protocol::ErrorCode::not_found,
                   "unknown, used or expired download link");
        return;
    }
    const bool head = req.method() == http::verb::head;
    auto prepare = [&](auto& res) {
        set_common_headers(res);
        res.set(http::field::content_type, entry->mime);
        res.set(http::field::content_disposition, content_disposition(entry->name));
        res.set(http::field::cache_control, "no-store");
        res.keep_alive(keep_alive);
        res.content_length(static_cast<std::uint64_t>(entry->size));
    };
    // A slow reader gets a minute plus a second per megabyte.
    beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(60 + entry->size / (1 << 20)));
    if (entry->bytes) {
        auto res = std::make_shared<http::response<http::string_body>>(http::status::ok, req.version());
        if (!head) res->body() = *entry->bytes;
        prepare(*res);
        write_response(std::move(res));
        return;
    }
    VerifiedFileBody::value_type body;
    if (const auto why = body.open(*entry->file, entry->identity, entry->sha256)) {
        // Gone or changed since the grab: what would arrive is not what the
        // content message promised.
        answer_error(http::status::conflict, keep_alive, protocol::ErrorCode::internal, *why);
        return;
    }
    if (head) {
        auto res = std::make_shared<http::response<http::empty_body>>(http::status::ok, req.version());
        prepare(*res);
        write_response(std::move(res));
        return;
    }
    auto res = std::make_shared<http::response<VerifiedFileBody>>(
        std::piecewise_construct, std::make_tuple(std::move(body)), std::make_tuple(http::status::ok, req.version()));
    prepare(*res);
    auto& r = *res;
    response_ = std::move(res);
    http::async_write(stream_, r,
                      [self = shared_from_this(), keep_alive, file = *entry->file](beast::error_code ec, std::size_t) {
                          self->response_.reset();
                          if (ec == DownloadCheck::changed) {
                              // Cut short: the phone sees fewer bytes than promised
                              // and keeps none; the next grab hashes the file again.
                              self->service_->forget_file(file);
                              beast::get_lowest_layer(self->stream_).close();
                              return;
                          }
                          if (ec) return;
                          self->after_response(keep_alive);
                      });
}


template <class Body>
void HttpSession::write_response(std::shared_ptr<http::response<Body>> response) {
    const bool keep_alive = response->keep_alive();
    auto& res = *response;
    response_ = std::move(response);
    http::async_write(stream_, res, [self = shared_from_this(), keep_alive](beast::error_code ec, std::size_t) {
        self->response_.reset();
        if (ec) return;  // the peer went away mid-response; the session ends and frees what it held
        self->after_response(keep_alive);
    });
}

void HttpSession::after_response(bool keep_alive) {
    if (watching_) {
        // After a long poll a read is under way already: it becomes the next
        // request once the client sends one, within the idle timeout. TLS
        // cannot shut down with a read outstanding, so an end is a plain close.
        if (keep_alive && !closing_) {
            resume_after_watch_ = true;
            arm_timer(kHandshakeTimeout, &HttpSession::on_idle_timer);
        } else {
            beast::get_lowest_layer(stream_).close();
        }
        return;
    }
    if (keep_alive && !closing_) {
        read_request();
        return;
    }
    if (linger_after_response_) {
        lingering_close(beast::get_lowest_layer(stream_), shared_from_this());
        return;
    }
    end_tls();
}

void HttpSession::end_tls() {
    beast::get_lowest_layer(stream_).expires_after(std::chrono::seconds(5));
    stream_.async_shutdown([self = shared_from_this()](beast::error_code) {
        beast::error_code ignored;
        beast::get_lowest_layer(self->stream_).socket().shutdown(net::ip::tcp::socket::shutdown_both, ignored);
    });
}


void HttpSession::shutdown() {
    net::post(executor_, [self = shared_from_this()] { self->do_shutdown(); });
}

void HttpSession::do_shutdown() {
    // Asked before the upgrade reached the strand: the WebSocket session stops.
    if (!state_) {
        if (auto next = next_.lock()) next->shutdown();
        return;
    }
    closing_ = true;
    // An open long poll is answered (the provider goes away: 1001), then the
    // connection closes; a response being written ends the connection once
    // written; anything else (a request being read, an upload, a connection
    // idle after a poll) is simply dropped.
    if (poll_pending_) {
        http_sessions_->cancel_poll(poll_ticket_);
        finish_poll(poll_serial_, {200, api_body({}, {}, kClosedGoingAway), false});
    } else if (!request_ || !request_->is_done() || (watching_ && !response_)) {
        beast::get_lowest_layer(stream_).close();
    }
}

void HttpSession::abort() {
    net::post(executor_, [self = shared_from_this()] {
        if (!self->state_) {
            if (auto next = self->next_.lock()) next->abort();
            return;
        }
        self->closing_ = true;
        beast::get_lowest_layer(self->stream_).close();
    });
}

}  // namespace umf::provider
