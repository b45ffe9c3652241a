// HttpConnection's part for the HTTPS transport (docs/PROTOCOL.md, "HTTPS
// transport"): the /api/ calls handed to ApiSessions, and the long poll,
// which waits on a timer of the strand while a read watches for the client
// leaving; that read becomes the start of the next request once the poll is
// answered.
#include "provider/net/http_connection.hpp"

#include <boost/asio/post.hpp>

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;

namespace {

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

void HttpConnection::serve_api(const HttpRequest& req) {
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
    ApiSessions::Reply reply;
    switch (call) {
        case Call::hello:
            reply = api_sessions_->hello(req.body(), peer_);
            break;
        case Call::message:
            reply = api_sessions_->message(session, req.body());
            break;
        case Call::close:
            reply = api_sessions_->close(session);
            break;
        case Call::events:
            start_poll(session, keep_alive);
            return;
        case Call::none:
            return;
    }
    api_response(reply.status, keep_alive, std::move(reply.body));
}

void HttpConnection::start_poll(std::string_view id, bool keep_alive) {
    const std::uint64_t poll = ++poll_serial_;
    // Called at most once, from any thread: the answer goes to this strand.
    auto waiter = [weak = weak_from_this(), executor = executor_, poll](ApiSessions::Reply reply) {
        net::post(executor, [weak, poll, reply = std::move(reply)]() mutable {
            if (auto self = weak.lock()) self->finish_poll(poll, std::move(reply));
        });
    };
    ApiSessions::PollStart start = api_sessions_->begin_poll(id, std::move(waiter));
    if (start.now) {
        api_response(start.now->status, keep_alive, std::move(start.now->body));
        return;
    }
    poll_pending_ = true;
    poll_ticket_ = start.ticket;
    poll_keep_alive_ = keep_alive;
    // The poll's own timer bounds it; the read below has no timeout.
    beast::get_lowest_layer(stream_).expires_never();
    arm_timer(std::chrono::duration_cast<std::chrono::milliseconds>(api_sessions_->options().poll_timeout),
              &HttpConnection::on_poll_timer);
    watch();
}

void HttpConnection::arm_timer(std::chrono::milliseconds after,
                            void (HttpConnection::*handler)(beast::error_code, std::uint64_t)) {
    const std::uint64_t serial = ++timer_serial_;
    timer_.expires_after(after);
    timer_.async_wait([self = shared_from_this(), handler, serial](beast::error_code ec) {
        ((*self).*handler)(ec, serial);
    });
}

void HttpConnection::on_poll_timer(beast::error_code ec, std::uint64_t serial) {
    if (ec || serial != timer_serial_ || !poll_pending_) return;
    // Nothing came: answered with no messages, unless an answer is already
    // on its way to this strand.
    if (auto reply = api_sessions_->end_poll(poll_ticket_)) finish_poll(poll_serial_, std::move(*reply));
}

void HttpConnection::on_idle_timer(beast::error_code ec, std::uint64_t serial) {
    if (ec || serial != timer_serial_ || !watching_) return;
    drop();  // kept alive after a poll, but nothing came
}

void HttpConnection::finish_poll(std::uint64_t poll, ApiSessions::Reply reply) {
    if (!poll_pending_ || poll != poll_serial_) return;
    poll_pending_ = false;
    ++timer_serial_;
    timer_.cancel();
    // The write gets the usual timeout (the watching read has none).
    restart_timeout();
    api_response(reply.status, poll_keep_alive_ && !closing_, std::move(reply.body));
}

void HttpConnection::watch() {
    // Reads whatever comes while the poll is open: nothing until the client
    // goes away (an error), or the start of its next request.
    if (buffer_.size() >= kMaxRequestHeaderBytes) return;  // a pipelining client waits for its answer
    watching_ = true;
    stream_.async_read_some(buffer_.prepare(2048),
                            beast::bind_front_handler(&HttpConnection::on_watch, shared_from_this()));
}

void HttpConnection::on_watch(beast::error_code ec, std::size_t bytes) {
    watching_ = false;
    if (ec) {
        // Gone (or closed by a timeout or a shutdown): the poll is dropped,
        // its HTTP session stays until it expires or the client comes back.
        if (poll_pending_) {
            poll_pending_ = false;
            api_sessions_->cancel_poll(poll_ticket_);
        }
        ++timer_serial_;
        timer_.cancel();
        drop();
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

}  // namespace umf::provider
