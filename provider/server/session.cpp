#include "server/session.hpp"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/detect_ssl.hpp>
#include <boost/asio/post.hpp>
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
#include "server/listener.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
namespace ssl = boost::asio::ssl;

namespace {

constexpr auto kHandshakeTimeout = std::chrono::seconds(30);
// A refused request's sender may still be sending what was refused: its
// bytes are read and dropped for this long, or up to this much, before the
// socket closes (lingering_close).
constexpr auto kLingerTime = std::chrono::seconds(5);
constexpr std::size_t kMaxLingerBytes = 64 << 20;
constexpr std::size_t kMaxRequestHeaderBytes = 8 * 1024;
// Bodies carry one message of the HTTPS transport (docs/PROTOCOL.md, "Limits").
constexpr std::size_t kMaxRequestBodyBytes = 16 * 1024;
// Replies waiting beyond this stop the reading until the peer takes them.
constexpr std::size_t kMaxQueuedReplies = 64;
// An upload's body goes to its file in chunks of this size.
constexpr std::size_t kUploadChunkBytes = 64 * 1024;
// The web client's share target (its manifest): a share is taken by the
// page's service worker; one that reaches the provider found none active.
constexpr const char* kSharePath = "/share";
constexpr const char* kShareUnavailable = "/?share=unavailable";

}  // namespace

Session::Session(net::ip::tcp::socket&& socket, ssl::context& tls, std::shared_ptr<const Service> service,
                 std::shared_ptr<SessionRegistry> registry, std::shared_ptr<HttpSessions> http_sessions)
    : ws_(std::move(socket), tls),
      service_(std::move(service)),
      registry_(std::move(registry)),
      http_sessions_(std::move(http_sessions)),
      timer_(ws_.get_executor()) {
    // Wrong pairing tokens are counted per address.
    beast::error_code ec;
    const auto remote = beast::get_lowest_layer(ws_).socket().remote_endpoint(ec);
    state_.peer = ec ? "unknown" : remote.address().to_string();
}

Session::~Session() {
    if (poll_pending_ && http_sessions_) http_sessions_->cancel_poll(poll_ticket_);
    if (upload_entry_) {
        // Torn down mid-upload without a handler to hear it (the server stopping).
        upload_sink_.reset();
        service_->puts().upload_failed(*upload_entry_, protocol::ErrorCode::interrupted,
                                       "the upload was cut off: the provider closed the connection");
    }
    service_->session_ended(state_);
    if (registry_) registry_->remove(this);
}

void Session::run() {
    registry_->add(this, weak_from_this());
    // What the service pushes to this session (a put's answer) comes on any
    // thread and is sent from the strand.
    state_.outbox = [weak = weak_from_this(), executor = ws_.get_executor()](std::uint64_t, std::string message) {
        net::post(executor, [weak, message = std::move(message)]() mutable {
            if (auto self = weak.lock()) self->push_message(std::move(message));
        });
    };
    net::dispatch(ws_.get_executor(), [self = shared_from_this()] {
        if (self->closing_) return;
        beast::get_lowest_layer(self->ws_).expires_after(kHandshakeTimeout);
        // Someone typing http:// gets told to use https:// rather than a
        // connection that just drops.
        beast::async_detect_ssl(beast::get_lowest_layer(self->ws_), self->buffer_,
                                beast::bind_front_handler(&Session::on_detect, self));
    });
}

void Session::on_detect(beast::error_code ec, bool tls) {
    if (ec || closing_) return;
    if (!tls) {
        static const std::string kPlainHttp =
            "HTTP/1.1 400 Bad Request\r\nServer: umf-provider\r\nContent-Type: text/plain; charset=utf-8\r\n"
            "Connection: close\r\nContent-Length: 60\r\n\r\n"
            "This is an HTTPS server: open the pairing link, https://...\n";
        net::async_write(beast::get_lowest_layer(ws_), net::buffer(kPlainHttp),
                         [self = shared_from_this()](beast::error_code, std::size_t) {
                             beast::error_code ignored;
                             beast::get_lowest_layer(self->ws_).socket().shutdown(net::ip::tcp::socket::shutdown_both,
                                                                                ignored);
                         });
        return;
    }
    ws_.next_layer().async_handshake(ssl::stream_base::server, buffer_.data(),
                                     [self = shared_from_this()](beast::error_code ec, std::size_t used) {
                                         self->buffer_.consume(used);
                                         self->on_tls_handshake(ec);
                                     });
}

void Session::on_tls_handshake(beast::error_code ec) {
    if (ec || closing_) return;
    read_request();
}

void Session::read_request() {
    // Also the idle timeout of a kept-alive connection.
    beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
    request_.reset();
    header_.emplace();
    header_->header_limit(kMaxRequestHeaderBytes);
    // The body's limit depends on the path: an upload's is its put's size,
    // anything else's kMaxRequestBodyBytes (on_header). Not boost::none:
    // Beast 1.74 compares the length with the optional, and none is less
    // than every length.
    header_->body_limit(std::numeric_limits<std::uint64_t>::max());
    buffer_.max_size(kMaxRequestHeaderBytes + kMaxRequestBodyBytes);
    http::async_read_header(ws_.next_layer(), buffer_, *header_,
                            beast::bind_front_handler(&Session::on_header, shared_from_this()));
}

void Session::request_failed(beast::error_code ec) {
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

void Session::on_header(beast::error_code ec, std::size_t) {
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
        beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
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
        net::post(ws_.get_executor(), [self = shared_from_this()] { self->on_request({}, 0); });
        return;
    }
    http::async_read(ws_.next_layer(), buffer_, *request_,
                     beast::bind_front_handler(&Session::on_request, shared_from_this()));
}

void Session::on_request(beast::error_code ec, std::size_t) {
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
    beast::get_lowest_layer(ws_).expires_never();
    // A requester that vanished (a phone locked, Wi-Fi gone) is pinged after
    // 30 s of silence and dropped after 60.
    auto timeouts = websocket::stream_base::timeout::suggested(beast::role_type::server);
    timeouts.idle_timeout = std::chrono::seconds(60);
    timeouts.keep_alive_pings = true;
    ws_.set_option(timeouts);
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::server, "umf-provider"); }));
    ws_.read_message_max(static_cast<std::size_t>(service_->config().limits.max_message_bytes));
    ws_.async_accept(req, beast::bind_front_handler(&Session::on_accept, shared_from_this()));
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

void Session::serve_api(const http::request<http::string_body>& req) {
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
            reply = http_sessions_->hello(req.body(), state_.peer);
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

void Session::api_response(int status, bool keep_alive, std::string body, const char* allow) {
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

void Session::answer_error(http::status status, bool keep_alive, const protocol::Error& error, const char* allow) {
    if (!keep_alive) {
        beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
        linger_after_response_ = true;
    }
    api_response(static_cast<int>(status), keep_alive, protocol::encode_error_body(error), allow);
}

void Session::answer_error(http::status status, bool keep_alive, protocol::ErrorCode code, const std::string& message,
                           const char* allow) {
    answer_error(status, keep_alive, protocol::Error{std::nullopt, code, message}, allow);
}

void Session::start_poll(std::string_view id, bool keep_alive) {
    const std::uint64_t poll = ++poll_serial_;
    // Called at most once, from any thread: the answer goes to this strand.
    auto waiter = [weak = weak_from_this(), executor = ws_.get_executor(), poll](HttpSessions::Reply reply) {
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
    beast::get_lowest_layer(ws_).expires_never();
    arm_timer(std::chrono::duration_cast<std::chrono::milliseconds>(http_sessions_->options().poll_timeout),
              &Session::on_poll_timer);
    watch();
}

void Session::arm_timer(std::chrono::milliseconds after, void (Session::*handler)(beast::error_code, std::uint64_t)) {
    const std::uint64_t serial = ++timer_serial_;
    timer_.expires_after(after);
    timer_.async_wait([self = shared_from_this(), handler, serial](beast::error_code ec) {
        ((*self).*handler)(ec, serial);
    });
}

void Session::on_poll_timer(beast::error_code ec, std::uint64_t serial) {
    if (ec || serial != timer_serial_ || !poll_pending_) return;
    // Nothing came: answered with no messages, unless an answer is already
    // on its way to this strand.
    if (auto reply = http_sessions_->end_poll(poll_ticket_)) finish_poll(poll_serial_, std::move(*reply));
}

void Session::on_idle_timer(beast::error_code ec, std::uint64_t serial) {
    if (ec || serial != timer_serial_ || !watching_) return;
    beast::get_lowest_layer(ws_).close();  // kept alive after a poll, but nothing came
}

void Session::finish_poll(std::uint64_t poll, HttpSessions::Reply reply) {
    if (!poll_pending_ || poll != poll_serial_) return;
    poll_pending_ = false;
    ++timer_serial_;
    timer_.cancel();
    // The write gets the usual timeout (the watching read has none).
    beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
    api_response(reply.status, poll_keep_alive_ && !closing_, std::move(reply.body));
}

void Session::watch() {
    // Reads whatever comes while the poll is open: nothing until the client
    // goes away (an error), or the start of its next request.
    if (buffer_.size() >= kMaxRequestHeaderBytes) return;  // a pipelining client waits for its answer
    watching_ = true;
    ws_.next_layer().async_read_some(buffer_.prepare(2048),
                                     beast::bind_front_handler(&Session::on_watch, shared_from_this()));
}

void Session::on_watch(beast::error_code ec, std::size_t bytes) {
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
        beast::get_lowest_layer(ws_).close();
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


void Session::start_upload() {
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
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(60 + size / (1 << 20)));
    if (expect_continue) {
        auto res = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
        auto& r = *res;
        response_ = std::move(res);
        http::async_write(ws_.next_layer(), r, [self = shared_from_this()](beast::error_code ec, std::size_t) {
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

void Session::read_upload() {
    if (upload_->is_done()) {
        finish_upload();
        return;
    }
    auto& body = upload_->get().body();
    body.data = upload_chunk_.data();
    body.size = upload_chunk_.size();
    http::async_read(ws_.next_layer(), buffer_, *upload_,
                     beast::bind_front_handler(&Session::on_upload, shared_from_this()));
}

void Session::on_upload(beast::error_code ec, std::size_t) {
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

void Session::finish_upload() {
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
    beast::get_lowest_layer(ws_).expires_after(kHandshakeTimeout);
    api_response(200, keep_alive && !closing_, encode_reply(done));
}

void Session::fail_upload(protocol::ErrorCode code, const std::string& message, bool answer) {
    upload_sink_.reset();  // the temporary file goes with it
    upload_.reset();
    upload_chunk_ = {};
    if (!upload_entry_) return;
    const protocol::Error error = service_->puts().upload_failed(*upload_entry_, code, message);
    upload_entry_.reset();
    if (!answer) {
        beast::get_lowest_layer(ws_).close();
        return;
    }
    const auto status = code == protocol::ErrorCode::too_large  ? http::status::payload_too_large
                        : code == protocol::ErrorCode::internal ? http::status::internal_server_error
                                                                : http::status::bad_request;
    answer_error(status, false, error);
}

void Session::push_message(std::string text) {
    // Only a WebSocket session is welcomed here (HTTPS ones live in HttpSessions).
    if (!websocket_ || closing_) return;
    send(std::move(text));
}

void Session::serve_http(const http::request<http::string_body>& req) {
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

void Session::serve_download(const http::request<http::string_body>& req) {
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
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(60 + entry->size / (1 << 20)));
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
    http::async_write(ws_.next_layer(), r,
                      [self = shared_from_this(), keep_alive, file = *entry->file](beast::error_code ec, std::size_t) {
                          self->response_.reset();
                          if (ec == DownloadCheck::changed) {
                              // Cut short: the phone sees fewer bytes than promised
                              // and keeps none; the next grab hashes the file again.
                              self->service_->forget_file(file);
                              beast::get_lowest_layer(self->ws_).close();
                              return;
                          }
                          if (ec) return;
                          self->after_response(keep_alive);
                      });
}


template <class Body>
void Session::write_response(std::shared_ptr<http::response<Body>> response) {
    const bool keep_alive = response->keep_alive();
    auto& res = *response;
    response_ = std::move(response);
    http::async_write(ws_.next_layer(), res, [self = shared_from_this(), keep_alive](beast::error_code ec, std::size_t) {
        self->response_.reset();
        if (ec) return;  // the peer went away mid-response; the session ends and frees what it held
        self->after_response(keep_alive);
    });
}

void Session::after_response(bool keep_alive) {
    if (watching_) {
        // After a long poll a read is under way already: it becomes the next
        // request once the client sends one, within the idle timeout. TLS
        // cannot shut down with a read outstanding, so an end is a plain close.
        if (keep_alive && !closing_) {
            resume_after_watch_ = true;
            arm_timer(kHandshakeTimeout, &Session::on_idle_timer);
        } else {
            beast::get_lowest_layer(ws_).close();
        }
        return;
    }
    if (keep_alive && !closing_) {
        read_request();
        return;
    }
    if (linger_after_response_) {
        lingering_close();
        return;
    }
    end_tls();
}

void Session::lingering_close() {
    // Closing a socket with unread bytes makes the kernel send a reset,
    // which can destroy the answer before the peer reads it: a sender still
    // writing the body that was refused would never see why. So the answer
    // is followed by our FIN (no TLS close_notify: the peer may be mid-record),
    // and what still comes is read and dropped until the peer closes.
    auto& tcp = beast::get_lowest_layer(ws_);
    beast::error_code ignored;
    tcp.socket().shutdown(net::ip::tcp::socket::shutdown_send, ignored);
    tcp.expires_after(kLingerTime);
    linger_buffer_ = std::make_unique<std::array<char, 16 * 1024>>();
    linger_bytes_ = 0;
    drain();
}

void Session::drain() {
    beast::get_lowest_layer(ws_).async_read_some(
        net::buffer(*linger_buffer_), [self = shared_from_this()](beast::error_code ec, std::size_t n) {
            self->linger_bytes_ += n;
            if (ec || self->linger_bytes_ > kMaxLingerBytes) {
                beast::get_lowest_layer(self->ws_).close();
                return;
            }
            self->drain();
        });
}

void Session::end_tls() {
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(5));
    ws_.next_layer().async_shutdown([self = shared_from_this()](beast::error_code) {
        beast::error_code ignored;
        beast::get_lowest_layer(self->ws_).socket().shutdown(net::ip::tcp::socket::shutdown_both, ignored);
    });
}


void Session::on_accept(beast::error_code ec) {
    if (ec) return;
    websocket_ = true;
    // The upgrade request is read: an idle session keeps no more buffer than
    // its next message needs (memory per idle requester, docs/BENCHMARKS.md).
    buffer_.shrink_to_fit();
    if (closing_) {
        if (!close_started_) close(close_code_);
        return;
    }
    read();
}

void Session::read() {
    reading_ = true;
    ws_.async_read(buffer_, beast::bind_front_handler(&Session::on_read, shared_from_this()));
}

void Session::on_read(beast::error_code ec, std::size_t) {
    reading_ = false;
    // The session ends here: closed by the peer, timed out, aborted, or
    // failed by Beast, which has sent its close (1009 for a message too
    // big, 1007 for text that is not UTF-8). The peer may still be sending
    // the rest of what failed it: closing under that would reset the
    // connection and could destroy the close before the peer reads it.
    if (ec) {
        if (!closing_ && ec != net::error::operation_aborted) lingering_close();
        return;
    }
    if (closing_) return;

    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    if (buffer_.capacity() > 4096) buffer_.shrink_to_fit();  // after a rare large message
    const Outcome outcome = ws_.got_binary() ? service_->handle_binary(state_) : service_->handle_text(state_, text);
    for (const auto& reply : outcome.replies) send(encode_reply(reply));
    if (outcome.close) {
        closing_ = true;
        close_after_queue_ = true;
        close_code_ = outcome.restart ? websocket::close_code::service_restart : websocket::close_code::policy_error;
        if (queue_.empty()) close(close_code_);
        return;
    }
    if (queue_.size() < kMaxQueuedReplies) read();
}

void Session::send(std::string text) {
    queue_.push_back(std::move(text));
    if (queue_.size() == 1) write_next();
}

void Session::write_next() {
    ws_.text(true);
    ws_.async_write(net::buffer(queue_.front()), beast::bind_front_handler(&Session::on_write, shared_from_this()));
}

void Session::on_write(beast::error_code ec, std::size_t) {
    if (ec) return;
    queue_.pop_front();
    if (!queue_.empty()) {
        write_next();
        return;
    }
    if (close_after_queue_) {
        if (!close_started_) close(close_code_);
        return;
    }
    if (!reading_ && !closing_) read();
}

void Session::close(websocket::close_code code) {
    close_started_ = true;
    ws_.async_close(code, beast::bind_front_handler(&Session::on_close, shared_from_this()));
}

void Session::on_close(beast::error_code) {
    // The closing handshake is over (or failed); the stream is torn down and
    // the session ends with its last handler.
}

void Session::shutdown() {
    net::post(ws_.get_executor(), [self = shared_from_this()] { self->do_shutdown(); });
}

void Session::do_shutdown() {
    if (close_started_) return;
    if (!closing_) {
        close_after_queue_ = true;
        close_code_ = websocket::close_code::going_away;
    }
    closing_ = true;
    if (!websocket_) {
        // Still in the TLS handshake, the HTTP request or the upgrade: an
        // accept under way finishes and then closes (on_accept); anything
        // earlier is simply dropped. An open long poll is answered (the
        // provider goes away: 1001), then the connection closes; one idle
        // after a poll is dropped.
        if (poll_pending_) {
            http_sessions_->cancel_poll(poll_ticket_);
            finish_poll(poll_serial_, {200, api_body({}, {}, kClosedGoingAway), false});
        } else if (!request_ || !request_->is_done() || (watching_ && !response_)) {
            beast::get_lowest_layer(ws_).close();
        }
        return;
    }
    if (queue_.empty()) close(close_code_);
}

void Session::abort() {
    net::post(ws_.get_executor(), [self = shared_from_this()] {
        self->closing_ = true;
        beast::get_lowest_layer(self->ws_).close();
    });
}

}  // namespace umf::provider
