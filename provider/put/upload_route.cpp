#include "provider/put/upload_route.hpp"

#include <algorithm>
#include <boost/beast/core/string.hpp>
#include <boost/beast/http/buffer_body.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <cctype>
#include <charconv>
#include <chrono>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/common/encode_reply.hpp"
#include "provider/net/http_response_headers.hpp"
#include "provider/put/direct_body_receive.hpp"
#include "provider/put/upload_sink.hpp"
#include "shared/protocol/http_error_body.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;

namespace {

// An upload's body goes to its file in chunks of this size.
constexpr std::size_t kUploadChunkBytes = 64 * 1024;
// A body at least this large, sent after "100 Continue", is read past the stream.
constexpr std::uint64_t kDirectReceiveBytes = 1 << 20;

// One request of an upload under way: its parser (the body in chunks), the
// link's checkout and the sink it claimed. Its pending handlers own it, and it
// holds the connection.
class Upload : public std::enable_shared_from_this<Upload> {
public:
    Upload(std::shared_ptr<HttpExchange> exchange, PutDesk& puts, UploadCheckout checkout)
        : exchange_(std::move(exchange)), puts_(puts), checkout_(std::move(checkout)) {}
    ~Upload();

    void start(http::request_parser<http::empty_body>&& header);

private:
    void read();
    void on_read(beast::error_code ec, std::size_t);
    // The rest of the body, `left` bytes, past the stream (direct_body_receive.hpp).
    void read_direct(std::uint64_t left);
    // Bytes of the body for the sink; false when the upload ended with them
    // (failed: answered with the reason when `answer`, else dropped).
    bool take(const char* data, std::size_t size, bool answer = true);
    void finish();
    void refuse_offset(std::int64_t held);
    // The connection broke (or a newer request took over): the bytes so far
    // wait with the link for the rest.
    void broke_off();
    // The upload failed for good: its file removed, the put's session told;
    // answered while the connection is there (`answer`), else dropped. The
    // answer's status follows the code unless `status` is given.
    void fail(protocol::ErrorCode code, const std::string& message, bool answer,
              std::optional<http::status> status = std::nullopt);
    // A resumed request's Upload-Prefix-SHA256, when it has one, against the
    // bytes held; false when the upload failed on it.
    bool prefix_matches(const http::request_parser<http::empty_body>& header, std::int64_t held);
    // A request's Upload-SHA256 (the hash of a put that left it out, named
    // after the bytes) given to the sink; false when the upload failed on it.
    bool take_named_hash(const http::request_parser<http::empty_body>& header);
    // Every byte is here but not the hash they must have: 202, and the link
    // waits for a request that names it.
    void await_hash();
    const UploadEntry& entry() const { return checkout_.entry; }

    std::shared_ptr<HttpExchange> exchange_;
    PutDesk& puts_;
    UploadCheckout checkout_;
    bool ended_ = false;  // the checkout given back
    bool direct_ = false;  // the body came past the stream: the connection ends after the answer
    std::uint64_t claim_ = 0;
    std::optional<http::request_parser<http::buffer_body>> parser_;
    std::vector<char> chunk_;
};

Upload::~Upload() {
    // Torn down mid-upload without a handler to hear it (the server
    // stopping): the bytes wait with the link like a broken connection's.
    if (!ended_) puts_.end_upload(checkout_, UploadEnd::broken);
}

// 64 hexadecimal digits, either case: a header's SHA-256.
bool is_sha256_hex(beast::string_view text) {
    return text.size() == 64 &&
           std::all_of(text.begin(), text.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

// The request's Upload-Offset: where its body starts in the file (0 when
// absent); nullopt when it is not a number.
std::optional<std::int64_t> upload_offset(const http::request_parser<http::empty_body>& header) {
    const beast::string_view text = header.get()["Upload-Offset"];
    if (text.empty()) return 0;
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < 0) return std::nullopt;
    return value;
}

void Upload::start(http::request_parser<http::empty_body>&& header) {
    const std::int64_t size = entry().size;
    // A request that cannot be right fails the put (it is no broken connection).
    const auto offset = upload_offset(header);
    const auto length = header.content_length();
    if (!offset || *offset > size || !length || header.chunked() ||
        *length != static_cast<std::uint64_t>(size - *offset)) {
        const std::int64_t from = offset && *offset <= size ? *offset : 0;
        const std::string why = "an upload from byte " + std::to_string(from) + " needs a Content-Length of " +
                                std::to_string(size - from);
        ended_ = true;
        if (checkout_.sink) checkout_.sink->discard();
        puts_.end_upload(checkout_, UploadEnd::failed);
        puts_.upload_failed(entry(), protocol::ErrorCode::interrupted, why);
        exchange_->answer_error(length && !header.chunked() ? http::status::bad_request : http::status::length_required,
                                false, protocol::ErrorCode::bad_request, why);
        return;
    }
    if (!checkout_.sink) {
        try {
            checkout_.sink = puts_.keep_upload_sink(checkout_, std::make_shared<UploadSink>(entry().folder, size, entry().sha256));
        } catch (const UploadError& e) {
            fail(e.code(), e.what(), true);
            return;
        } catch (const std::exception& e) {
            fail(protocol::ErrorCode::internal, e.what(), true);
            return;
        }
    }
    const auto claim = checkout_.sink->claim();
    claim_ = claim.claim;
    if (*offset != claim.received) {
        ended_ = true;
        puts_.end_upload(checkout_, UploadEnd::broken);
        refuse_offset(claim.received);
        return;
    }
    if (!prefix_matches(header, claim.received) || !take_named_hash(header)) return;
    const bool expect_continue = beast::iequals(header.get()[http::field::expect], "100-continue");
    parser_.emplace(std::move(header));
    parser_->body_limit(static_cast<std::uint64_t>(size - claim.received));
    exchange_->buffer().max_size(std::numeric_limits<std::size_t>::max());
    chunk_.resize(kUploadChunkBytes);
    // A slow sender gets a minute plus a second per megabyte, as downloads.
    beast::get_lowest_layer(exchange_->stream())
        .expires_after(std::chrono::seconds(60 + (size - claim.received) / (1 << 20)));
    if (!expect_continue) {
        read();
        return;
    }
    auto res = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
    auto& r = *res;
    const std::uint64_t left = static_cast<std::uint64_t>(size - claim.received);
    send_response(exchange_->stream(), r, [self = shared_from_this(), res = std::move(res), left](beast::error_code ec) {
        if (ec) {
            self->broke_off();
            return;
        }
        // The client waited for this answer: nothing of the body is in the
        // stream yet, so a large one can go past it.
        if (left >= kDirectReceiveBytes && direct_receive_possible(*self->exchange_)) {
            self->read_direct(left);
            return;
        }
        self->read();
    });
}

bool Upload::prefix_matches(const http::request_parser<http::empty_body>& header, std::int64_t held) {
    const beast::string_view expected = header.get()["Upload-Prefix-SHA256"];
    if (expected.empty()) return true;
    if (!is_sha256_hex(expected)) {
        fail(protocol::ErrorCode::bad_request, "Upload-Prefix-SHA256 is not 64 hexadecimal digits", true);
        return false;
    }
    std::string digest;
    try {
        digest = checkout_.sink->received_sha256();
    } catch (const UploadError& e) {
        fail(e.code(), e.what(), true);
        return false;
    }
    if (beast::iequals(digest, expected)) return true;
    // The bytes held were read from the file earlier: the file changed since
    // (or they are not its bytes), and the rest could only fail at the end.
    fail(protocol::ErrorCode::interrupted,
         "the " + std::to_string(held) + " bytes the screen holds are not the start of this file (it changed while "
         "it was being sent); nothing was kept, put it again",
         true, http::status::precondition_failed);
    return false;
}

bool Upload::take_named_hash(const http::request_parser<http::empty_body>& header) {
    const beast::string_view named = header.get()["Upload-SHA256"];
    if (named.empty()) return true;
    if (!is_sha256_hex(named)) {
        fail(protocol::ErrorCode::bad_request, "Upload-SHA256 is not 64 hexadecimal digits", true);
        return false;
    }
    try {
        checkout_.sink->expect_sha256(std::string(named));
    } catch (const UploadError& e) {
        fail(e.code(), e.what(), true);
        return false;
    }
    return true;
}

void Upload::read_direct(std::uint64_t left) {
    direct_ = true;
    receive_body_direct(
        exchange_, left, std::chrono::seconds(60),
        [self = shared_from_this()](const char* data, std::size_t size) { return self->take(data, size); },
        [self = shared_from_this()](beast::error_code ec) {
            if (self->ended_ || !self->parser_) return;
            if (ec) {
                self->broke_off();
                return;
            }
            self->finish();
        });
}

bool Upload::take(const char* data, std::size_t size, bool answer) {
    if (ended_ || !parser_) return false;
    try {
        checkout_.sink->write(data, size, claim_);
        return true;
    } catch (const UploadError& e) {
        if (checkout_.sink->superseded(claim_)) {
            broke_off();
            return false;
        }
        fail(e.code(), e.what(), answer);
        return false;
    }
}

// The requester sends from another byte than the provider holds: it asks
// again (HEAD) and sends from there. The connection ends as soon as the
// answer is out, without reading on: the body is of no use, and a browser
// may be sending the whole file again.
void Upload::refuse_offset(std::int64_t held) {
    auto res = std::make_shared<http::response<http::string_body>>(http::status::conflict, 11);
    set_common_headers(*res);
    res->set(http::field::content_type, "application/json");
    res->set("Upload-Offset", std::to_string(held));
    res->body() = protocol::encode_error_body(protocol::Error{
        std::nullopt, protocol::ErrorCode::interrupted,
        "the upload holds " + std::to_string(held) + " bytes; send from there"});
    res->keep_alive(false);
    res->prepare_payload();
    auto& r = *res;
    send_response(exchange_->stream(), r,
                  [held_exchange = exchange_, res = std::move(res)](beast::error_code) { held_exchange->drop(); });
}

void Upload::read() {
    if (parser_->is_done()) {
        finish();
        return;
    }
    auto& body = parser_->get().body();
    body.data = chunk_.data();
    body.size = chunk_.size();
    http::async_read(exchange_->stream(), exchange_->buffer(), *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t n) { self->on_read(ec, n); });
}

void Upload::on_read(beast::error_code ec, std::size_t) {
    if (!parser_ || ended_) return;
    if (ec == http::error::need_buffer) ec = {};
    const std::size_t got = chunk_.size() - parser_->get().body().size;
    if (got > 0 && !take(chunk_.data(), got, !ec)) return;
    if (ec || exchange_->stopping()) {
        broke_off();
        return;
    }
    read();
}

void Upload::broke_off() {
    parser_.reset();
    chunk_ = {};
    if (!ended_) {
        ended_ = true;
        puts_.end_upload(checkout_, UploadEnd::broken);
    }
    exchange_->drop();
}

void Upload::await_hash() {
    const bool keep_alive = parser_->get().keep_alive() && !direct_;
    parser_.reset();
    chunk_ = {};
    ended_ = true;
    puts_.end_upload(checkout_, UploadEnd::broken);  // as a cut one: the link waits for the rest, here the hash
    auto res = std::make_shared<http::response<http::empty_body>>(http::status::accepted, 11);
    set_common_headers(*res);
    res->set("Upload-Offset", std::to_string(entry().size));
    res->set(http::field::cache_control, "no-store");
    res->keep_alive(keep_alive && !exchange_->stopping());
    res->prepare_payload();
    exchange_->restart_timeout();
    write_response(*exchange_, std::move(res));
}

void Upload::finish() {
    if (!checkout_.sink->knows_sha256()) {
        await_hash();
        return;
    }
    std::string stored;
    try {
        stored = checkout_.sink->store(entry().name, claim_);
    } catch (const UploadError& e) {
        fail(e.code(), e.what(), true);
        return;
    }
    const bool keep_alive = parser_->get().keep_alive() && !direct_;
    parser_.reset();
    chunk_ = {};
    ended_ = true;
    puts_.end_upload(checkout_, UploadEnd::stored);
    const protocol::Message done = puts_.upload_done(entry(), stored);
    exchange_->restart_timeout();
    exchange_->answer_json(200, keep_alive && !exchange_->stopping(), encode_reply(done));
}

void Upload::fail(protocol::ErrorCode code, const std::string& message, bool answer,
                  std::optional<http::status> status) {
    if (checkout_.sink) checkout_.sink->discard();  // the temporary file goes
    parser_.reset();
    chunk_ = {};
    if (ended_) return;
    ended_ = true;
    puts_.end_upload(checkout_, UploadEnd::failed);
    const protocol::Error error = puts_.upload_failed(entry(), code, message);
    if (!answer) {
        exchange_->drop();
        return;
    }
    if (!status)
        status = code == protocol::ErrorCode::too_large  ? http::status::payload_too_large
                 : code == protocol::ErrorCode::internal ? http::status::internal_server_error
                                                         : http::status::bad_request;
    exchange_->answer_error(*status, false, error);
}

// HEAD /up/...: how much of the upload the provider holds.
void answer_received(HttpExchange& exchange, std::int64_t received, std::int64_t size) {
    auto res = std::make_shared<http::response<http::empty_body>>(http::status::ok, 11);
    set_common_headers(*res);
    res->set("Upload-Offset", std::to_string(received));
    res->set("Upload-Length", std::to_string(size));
    res->set(http::field::cache_control, "no-store");
    res->keep_alive(false);
    write_response(exchange, std::move(res));
}

}  // namespace

void serve_upload(HttpExchange& exchange, http::request_parser<http::empty_body>&& header, PutDesk& puts) {
    const auto& req = header.get();
    const beast::string_view target = req.target();
    const std::string_view link(target.data(), target.size());
    if (req.method() == http::verb::head) {
        auto checkout = puts.begin_upload(link);
        if (!checkout) {
            exchange.answer_error(http::status::not_found, false, protocol::ErrorCode::not_found,
                                  "unknown, finished or expired upload link");
            return;
        }
        const std::int64_t received = checkout->sink ? checkout->sink->received() : 0;
        puts.end_upload(*checkout, UploadEnd::broken);  // only asked: the link waits on
        answer_received(exchange, received, checkout->entry.size);
        return;
    }
    if (req.method() != http::verb::put) {
        exchange.answer_error(http::status::method_not_allowed, false, protocol::ErrorCode::bad_request,
                              "an upload is a PUT (or a HEAD asking how much arrived)", "PUT, HEAD");
        return;
    }
    auto checkout = puts.begin_upload(link);
    if (!checkout) {
        exchange.answer_error(http::status::not_found, false, protocol::ErrorCode::not_found,
                              "unknown, finished or expired upload link");
        return;
    }
    std::make_shared<Upload>(exchange.hold(), puts, std::move(*checkout))->start(std::move(header));
}

}  // namespace umf::provider
