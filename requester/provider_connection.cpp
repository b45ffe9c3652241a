#include "requester/provider_connection.hpp"

#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <stdexcept>
#include <utility>

#include "requester/cli.hpp"
#include "requester/grab_failure.hpp"
#include "requester/transfer_text.hpp"

namespace umf::requester {

namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace p = protocol;
using Clock = std::chrono::steady_clock;


std::optional<p::RequestId> reply_id(const p::Message& m) {
    if (const auto* t = std::get_if<p::Target>(&m)) return t->id;
    if (const auto* c = std::get_if<p::Content>(&m)) return c->id;
    if (const auto* e = std::get_if<p::Error>(&m)) return e->id;
    if (const auto* s = std::get_if<p::PutStatus>(&m)) return s->id;
    return std::nullopt;
}

}  // namespace

ProviderConnection::ProviderConnection(protocol::PairingUrl url, NetTimeouts timeouts)
    : url_(std::move(url)), timeouts_(timeouts), work_(io_.get_executor()), tls_(make_pinned_client_context()) {}

ProviderConnection::~ProviderConnection() {
    // Pending operations end with operation_aborted once the socket is
    // closed; running them out keeps their handlers from outliving us.
    if (ws_) {
        beast::error_code ec;
        beast::get_lowest_layer(*ws_).socket().close(ec);
    }
    work_.reset();
    io_.restart();
    io_.run_for(std::chrono::seconds(1));
}

void ProviderConnection::check_alive() const {
    if (!failure_code_.empty()) throw GrabFailure(failure_code_, failure_message_, failure_exit_);
}

p::Welcome ProviderConnection::open(const std::string& client, const std::optional<std::string>& device) {
    ws_ = std::make_unique<Ws>(io_.get_executor(), tls_);
    connect_pinned(io_, ws_->next_layer(), url_, timeouts_);

    ws_->set_option(websocket::stream_base::timeout{timeouts_.handshake, websocket::stream_base::none(), false});
    ws_->set_option(websocket::stream_base::decorator(
        [](websocket::request_type& req) { req.set(http::field::user_agent, user_agent()); }));
    ws_->read_message_max(p::kMaxReplyBytes);
    bool done = false;
    beast::error_code ec;
    ws_->async_handshake(url_.authority(), "/ws", [&](beast::error_code e) {
        ec = e;
        done = true;
    });
    if (!run_until(io_, done, Clock::now() + timeouts_.handshake + std::chrono::seconds(1),
                   [&] { beast::get_lowest_layer(*ws_).close(); }) ||
        ec == beast::error::timeout)
        throw GrabFailure("connection",
                          "the WebSocket handshake with " + url_.authority() + " did not finish within " +
                              seconds_text(timeouts_.handshake),
                          kConnection);
    if (ec)
        throw GrabFailure("connection",
                          "the provider at " + url_.authority() + " refused the WebSocket on /ws: " + ec.message(),
                          kConnection);
    open_ = true;
    start_read();

    const p::RequestId hello_id{std::int64_t{1}};
    p::Hello hello{hello_id, url_.token, client};
    hello.device = device;
    send(hello);
    const auto deadline = Clock::now() + timeouts_.reply;
    while (inbox_.empty() && failure_code_.empty() && Clock::now() < deadline) io_.run_one_until(deadline);
    if (inbox_.empty()) {
        check_alive();
        throw GrabFailure("timeout", "the provider did not answer the hello within " + seconds_text(timeouts_.reply),
                          kConnection);
    }
    p::Message first = std::move(inbox_.front());
    inbox_.pop_front();
    if (auto* w = std::get_if<p::Welcome>(&first)) return std::move(*w);
    if (const auto* e = std::get_if<p::Error>(&first)) {
        if (e->code == p::ErrorCode::unauthorized)
            throw GrabFailure("unauthorized",
                              "the provider refused the pairing token (" + e->message +
                                  "); pair again with the provider's current URL",
                              kConnection);
        throw GrabFailure(p::to_string(e->code), "the provider refused the hello: " + e->message, kConnection);
    }
    throw GrabFailure("protocol", std::string("the provider answered the hello with a ") + p::type_name(first),
                      kConnection);
}

void ProviderConnection::start_read() {
    reading_ = true;
    ws_->async_read(read_buffer_, [this](beast::error_code ec, std::size_t) {
        reading_ = false;
        if (ec) {
            open_ = false;
            if (failure_code_.empty()) {
                failure_code_ = "connection";
                failure_exit_ = kConnection;
                if (ec == websocket::error::closed &&
                    ws_->reason().code == static_cast<std::uint16_t>(websocket::close_code::service_restart)) {
                    // The provider's screens changed: the field this session
                    // was given no longer holds; a new connection gets the new one.
                    failure_message_ = "the provider's screens changed; connect again to get the new field";
                } else if (ec == websocket::error::closed) {
                    const auto& reason = ws_->reason();
                    failure_message_ = "the provider closed the connection (code " + std::to_string(reason.code) +
                                       (reason.reason.empty() ? std::string() : ", " + std::string(reason.reason.data(), reason.reason.size())) +
                                       ")";
                } else {
                    failure_message_ = "the connection to the provider failed: " + ec.message();
                }
            }
            return;
        }
        const std::string text = beast::buffers_to_string(read_buffer_.data());
        read_buffer_.consume(read_buffer_.size());
        if (!ws_->got_text()) {
            failure_code_ = "protocol";
            failure_message_ = "the provider sent a binary frame; version 1 has only text messages";
            failure_exit_ = kConnection;
        } else {
            auto parsed = p::parse_message(text, p::kRequesterLimits);
            if (auto* m = std::get_if<p::Message>(&parsed)) {
                inbox_.push_back(std::move(*m));
            } else {
                // Our own provider never sends this: a version mismatch or a
                // bug, and guessing past it could grab the wrong thing.
                failure_code_ = "protocol";
                failure_message_ = "the provider sent a message this requester cannot read: " +
                                   std::get<p::ProtocolError>(parsed).message;
                failure_exit_ = kConnection;
            }
        }
        if (failure_code_.empty()) start_read();
    });
}

void ProviderConnection::send(const p::Message& message) {
    check_alive();
    if (!open_) throw GrabFailure("connection", "the connection to the provider is closed", kConnection);
    std::string problem;
    auto text = p::try_encode(message, &problem);
    if (!text) throw GrabFailure("internal", std::string("cannot encode a ") + p::type_name(message) + ": " + problem,
                                 kConnection);
    outbox_.push_back(std::move(*text));
    if (!writing_) write_next();
}

void ProviderConnection::write_next() {
    writing_ = true;
    ws_->text(true);
    ws_->async_write(net::buffer(outbox_.front()), [this](beast::error_code ec, std::size_t) {
        writing_ = false;
        outbox_.pop_front();
        if (ec) {
            if (failure_code_.empty()) {
                failure_code_ = "connection";
                failure_message_ = "cannot send to the provider: " + ec.message();
                failure_exit_ = kConnection;
            }
            open_ = false;
            return;
        }
        if (!outbox_.empty()) write_next();
    });
}

std::vector<p::Message> ProviderConnection::poll() {
    if (io_.stopped()) io_.restart();
    io_.poll();
    std::vector<p::Message> out(std::make_move_iterator(inbox_.begin()), std::make_move_iterator(inbox_.end()));
    inbox_.clear();
    if (out.empty()) check_alive();
    return out;
}

std::vector<p::Message> ProviderConnection::wait_any(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (inbox_.empty()) {
        check_alive();
        if (Clock::now() >= deadline) break;
        if (io_.stopped()) io_.restart();
        io_.run_one_until(deadline);
    }
    return poll();
}

p::Message ProviderConnection::wait_reply(const p::RequestId& id, const char* what) {
    return wait_reply(id, what, timeouts_.reply);
}

p::Message ProviderConnection::wait_reply(const p::RequestId& id, const char* what, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    for (;;) {
        for (auto it = inbox_.begin(); it != inbox_.end(); ++it) {
            if (reply_id(*it) == id) {
                p::Message m = std::move(*it);
                inbox_.erase(it);
                return m;
            }
        }
        check_alive();
        if (Clock::now() >= deadline)
            throw GrabFailure("timeout",
                              std::string("the provider did not answer the ") + what + " within " +
                                  seconds_text(timeout),
                              kConnection);
        if (io_.stopped()) io_.restart();
        io_.run_one_until(deadline);
    }
}

void ProviderConnection::close() {
    if (!ws_) return;
    try {
        if (open_ && failure_code_.empty()) {
            // Let queued messages go out first: a close frame overtaking them
            // would drop the last aim the provider should see.
            bool flushed = false;
            const auto deadline = Clock::now() + std::chrono::seconds(2);
            while (writing_ && failure_code_.empty() && Clock::now() < deadline) io_.run_one_until(deadline);
            flushed = !writing_;
            if (flushed && failure_code_.empty()) {
                bool done = false;
                ws_->async_close(websocket::close_code::normal, [&](beast::error_code) { done = true; });
                run_until(io_, done, Clock::now() + std::chrono::seconds(2),
                          [&] { beast::get_lowest_layer(*ws_).close(); });
            }
        }
    } catch (const std::exception&) {
        // Closing is a courtesy; the socket goes below either way.
    }
    open_ = false;
    beast::error_code ec;
    beast::get_lowest_layer(*ws_).socket().close(ec);
}

}  // namespace umf::requester
