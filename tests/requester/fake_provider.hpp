// A stand-in provider for the requester's tests: TLS with a provider
// identity, the WebSocket session (welcome with the default field, a target
// per aim, a scripted content per grab) and the one-time downloads, with
// every answer under the test's control; it also counts what arrived, so a
// test can tell that a refused certificate kept the hello from being sent.
// The real provider (provider/net under provider/service) serves the tests
// that need it; this one gives the answers a real one would not (a file
// that changes, a broken download) on cue.
#pragma once

#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "provider/service/service.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/http_error_body.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::test {

// What a grab answers and what its download link serves.
struct FakeContent {
    protocol::ContentKind kind = protocol::ContentKind::file;
    std::string title = "report.pdf - Document Viewer";
    std::string url;                      // kind url
    std::string name = "report.pdf";      // kind file or snapshot
    std::string body = "%PDF-1.4 pretend this is a document\n";
    std::optional<std::int64_t> size;     // announced; body.size() unless set
    std::optional<std::string> sha256;    // announced; none unless set
    unsigned status = 200;                // the download's HTTP status
    std::optional<std::size_t> sent_bytes;  // how much of the first answer's body is sent (a cut-off transfer)
    // A request for the rest (Range: bytes=N-) gets it as 206 when this is
    // 206, else this status with an error body (404: the link expired; 409:
    // the file changed, with `resume_reason`).
    unsigned resume_status = 206;
    std::string resume_reason = "the file changed since it was offered; grab again";
    // Shown from the grab's answer on: the download's connection meets
    // another certificate than the session's.
    std::optional<provider::TlsIdentity> download_identity;
};

class FakeProvider {
public:
    FakeProvider(provider::TlsIdentity identity, std::string token)
        : identity_(std::move(identity)), current_(identity_), token_(std::move(token)), tls_(boost::asio::ssl::context::tls_server),
          acceptor_(io_, {boost::asio::ip::make_address("127.0.0.1"), 0}) {
        provider::configure_server_context(tls_, current_);
        accept();
        thread_ = std::thread([this] { io_.run(); });
    }
    ~FakeProvider() {
        boost::asio::post(io_, [this] { acceptor_.close(); });
        thread_.join();
        join_connections();
    }

    // Waits for the connections so far to end (they do when the requester's
    // process has): the counts below are final afterwards.
    void join_connections() {
        std::vector<std::thread> threads;
        {
            std::lock_guard lock(mutex_);
            threads.swap(connections_);
        }
        for (auto& t : threads) t.join();
    }

    unsigned short port() const { return acceptor_.local_endpoint().port(); }
    const std::string& fingerprint() const { return identity_.fingerprint; }

    void set_content(FakeContent c) {
        std::lock_guard lock(mutex_);
        content_ = std::move(c);
        answered_ = 0;
    }
    // HTTP requests read after a completed TLS handshake (the WebSocket
    // upgrade included): none when the client refused the certificate.
    int requests() const { return requests_; }
    int hellos() const { return hellos_; }
    int grabs() const { return grabs_; }
    int downloads() const { return downloads_; }
    int aims() const { return aims_; }
    int seekings() const { return seekings_; }

private:
    using Tls = boost::beast::ssl_stream<boost::asio::ip::tcp::socket>;

    void accept() {
        acceptor_.async_accept([this](boost::system::error_code ec, boost::asio::ip::tcp::socket socket) {
            if (ec) return;  // closed
            std::lock_guard lock(mutex_);
            connections_.emplace_back([this, s = std::move(socket)]() mutable { serve(std::move(s)); });
            accept();
        });
    }

    // One connection, synchronously on its own thread; it ends when the
    // requester's process does, which closes the socket.
    void serve(boost::asio::ip::tcp::socket socket) {
        namespace http = boost::beast::http;
        namespace websocket = boost::beast::websocket;
        boost::system::error_code ec;
        Tls tls(std::move(socket), tls_);
        tls.handshake(boost::asio::ssl::stream_base::server, ec);
        if (ec) return;
        boost::beast::flat_buffer buffer;
        http::request<http::string_body> req;
        http::read(tls, buffer, req, ec);
        if (ec) return;
        ++requests_;
        if (websocket::is_upgrade(req)) {
            websocket::stream<Tls&> ws(tls);
            ws.accept(req, ec);
            if (!ec) session(ws);
            return;
        }
        download(tls, std::string(req.target()), std::string(req[boost::beast::http::field::range]),
                 std::string(req[boost::beast::http::field::authorization]));
    }

    template <class Ws>
    void session(Ws& ws) {
        namespace p = protocol;
        const auto config = provider::default_service_config();
        for (;;) {
            boost::beast::flat_buffer buffer;
            boost::system::error_code ec;
            ws.read(buffer, ec);
            if (ec) return;
            auto parsed = p::parse_message(boost::beast::buffers_to_string(buffer.data()));
            const auto* m = std::get_if<p::Message>(&parsed);
            if (!m) return;
            std::optional<p::Message> reply;
            bool close = false;
            if (const auto* h = std::get_if<p::Hello>(m)) {
                ++hellos_;
                if (h->token == token_) {
                    reply = p::Welcome{h->id, {"fake-desk", "fake-provider/1"}, config.screens.field, config.overlay,
                                       config.limits};
                } else {
                    reply = p::Error{h->id, p::ErrorCode::unauthorized, "unknown pairing token"};
                    close = true;
                }
            } else if (std::holds_alternative<p::Seeking>(*m)) {
                ++seekings_;
            } else if (const auto* a = std::get_if<p::Aim>(m)) {
                ++aims_;
                std::lock_guard lock(mutex_);
                reply = p::Target{a->id, a->point, content_.kind, content_.title};
            } else if (const auto* g = std::get_if<p::Grab>(m)) {
                ++grabs_;
                std::lock_guard lock(mutex_);
                p::Content c;
                c.id = g->id;
                c.kind = content_.kind;
                c.title = content_.title;
                if (c.kind == p::ContentKind::url) c.url = content_.url;
                if (c.kind == p::ContentKind::file || c.kind == p::ContentKind::snapshot) {
                    c.name = content_.name;
                    c.mime = "application/pdf";
                    c.size = content_.size.value_or(static_cast<std::int64_t>(content_.body.size()));
                    c.sha256 = content_.sha256;
                    c.download = "/dl/link" + std::to_string(grabs_.load());
                    if (content_.download_identity) current_.replace(*content_.download_identity);
                }
                reply = c;
            }
            if (reply) {
                ws.text(true);
                ws.write(boost::asio::buffer(p::encode(*reply)), ec);
                if (ec) return;
            }
            if (close) {
                ws.close(boost::beast::websocket::close_code::policy_error, ec);
                return;
            }
        }
    }

    // As the real one, a link is only for the session's token (401 without it).
    void download(Tls& tls, const std::string& target, const std::string& range, const std::string& authorization) {
        namespace http = boost::beast::http;
        FakeContent c;
        int nth = 0;  // of the answers since the content was set
        {
            std::lock_guard lock(mutex_);
            c = content_;
            nth = ++answered_;
        }
        ++downloads_;
        boost::system::error_code ec;
        std::size_t from = 0;
        if (range.rfind("bytes=", 0) == 0 && range.back() == '-') from = std::stoul(range.substr(6));
        const unsigned status = target.rfind("/dl/", 0) != 0           ? 404
                                : authorization != "Bearer " + token_ ? 401
                                : from > 0                              ? c.resume_status
                                                                        : c.status;
        if (status != 200 && status != 206) {
            http::response<http::string_body> res(static_cast<http::status>(status), 11);
            res.set(http::field::content_type, "application/json");
            res.body() = protocol::encode_error_body(protocol::Error{
                std::nullopt,
                status == 404   ? protocol::ErrorCode::not_found
                : status == 401 ? protocol::ErrorCode::unauthorized
                                : protocol::ErrorCode::internal,
                status == 404   ? "unknown, finished or expired download link"
                : status == 401 ? "a download link is used with the session's pairing token"
                : status == 409 ? c.resume_reason
                                : "the provider failed"});
            res.prepare_payload();
            http::write(tls, res, ec);
            return;
        }
        // Content-Length is the whole answer's even when less is sent, as
        // when a transfer breaks off.
        const std::string rest = c.body.substr(std::min(from, c.body.size()));
        std::string head = status == 206 ? "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes " + std::to_string(from) +
                                               "-" + std::to_string(c.body.size() - 1) + "/" +
                                               std::to_string(c.body.size()) + "\r\n"
                                         : "HTTP/1.1 200 OK\r\n";
        head += "Content-Type: application/pdf\r\nContent-Length: " + std::to_string(rest.size()) +
                "\r\nETag: \"sha256-fake\"\r\nContent-Disposition: attachment\r\nConnection: close\r\n\r\n";
        head += nth == 1 ? rest.substr(0, c.sent_bytes.value_or(rest.size())) : rest;
        boost::asio::write(tls, boost::asio::buffer(head), ec);
        tls.shutdown(ec);
    }

    provider::TlsIdentity identity_;
    provider::CurrentIdentity current_;
    std::string token_;
    boost::asio::io_context io_;
    boost::asio::ssl::context tls_;
    boost::asio::ip::tcp::acceptor acceptor_;
    std::thread thread_;
    std::mutex mutex_;
    std::vector<std::thread> connections_;
    FakeContent content_;
    int answered_ = 0;
    std::atomic<int> requests_{0}, hellos_{0}, grabs_{0}, downloads_{0}, aims_{0}, seekings_{0};
};

}  // namespace umf::test
