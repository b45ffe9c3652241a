#include "provider/put/upload_route.hpp"

#include <boost/beast/core/string.hpp>
#include <boost/beast/http/buffer_body.hpp>
#include <boost/beast/http/read.hpp>
#include <chrono>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "provider/common/encode_reply.hpp"
#include "provider/put/upload_sink.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;

namespace {

// An upload's body goes to its file in chunks of this size.
constexpr std::size_t kUploadChunkBytes = 64 * 1024;

// One upload under way: its parser (the body in chunks), the accepted put and
// the file the bytes go to. Its pending handlers own it, and it holds the
// connection.
class Upload : public std::enable_shared_from_this<Upload> {
public:
    Upload(std::shared_ptr<HttpExchange> exchange, PutDesk& puts, UploadEntry entry)
        : exchange_(std::move(exchange)), puts_(puts), entry_(std::move(entry)) {}
    ~Upload();

    void start(http::request_parser<http::empty_body>&& header);

private:
    void read();
    void on_read(beast::error_code ec, std::size_t);
    void finish();
    // The upload failed: its file removed, the put's session told; answered
    // while the connection is there (`answer`), else the connection dropped.
    void fail(protocol::ErrorCode code, const std::string& message, bool answer);

    std::shared_ptr<HttpExchange> exchange_;
    PutDesk& puts_;
    std::optional<UploadEntry> entry_;  // until the put's session is told how it ended
    std::optional<http::request_parser<http::buffer_body>> parser_;
    std::unique_ptr<UploadSink> sink_;
    std::vector<char> chunk_;
};

Upload::~Upload() {
    if (!entry_) return;
    // Torn down mid-upload without a handler to hear it (the server stopping).
    sink_.reset();
    puts_.upload_failed(*entry_, protocol::ErrorCode::interrupted,
                        "the upload was cut off: the provider closed the connection");
}

void Upload::start(http::request_parser<http::empty_body>&& header) {
    const std::int64_t size = entry_->size;
    try {
        sink_ = std::make_unique<UploadSink>(entry_->folder, size, entry_->sha256);
    } catch (const UploadError& e) {
        fail(e.code(), e.what(), true);
        return;
    } catch (const std::exception& e) {
        fail(protocol::ErrorCode::internal, e.what(), true);
        return;
    }
    const bool expect_continue = beast::iequals(header.get()[http::field::expect], "100-continue");
    parser_.emplace(std::move(header));
    parser_->body_limit(static_cast<std::uint64_t>(size));
    exchange_->buffer().max_size(std::numeric_limits<std::size_t>::max());
    chunk_.resize(kUploadChunkBytes);
    // A slow sender gets a minute plus a second per megabyte, as downloads.
    beast::get_lowest_layer(exchange_->stream()).expires_after(std::chrono::seconds(60 + size / (1 << 20)));
    if (!expect_continue) {
        read();
        return;
    }
    auto res = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
    auto& r = *res;
    http::async_write(exchange_->stream(), r,
                      [self = shared_from_this(), res = std::move(res)](beast::error_code ec, std::size_t) {
                          if (ec) {
                              self->fail(protocol::ErrorCode::interrupted, "the upload broke off: " + ec.message(),
                                         false);
                              return;
                          }
                          self->read();
                      });
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
    if (!parser_ || !sink_) return;
    if (ec == http::error::need_buffer) ec = {};
    const std::size_t got = chunk_.size() - parser_->get().body().size;
    if (got > 0) {
        try {
            sink_->write(chunk_.data(), got);
        } catch (const UploadError& e) {
            fail(e.code(), e.what(), !ec);
            return;
        }
    }
    if (ec) {
        fail(protocol::ErrorCode::interrupted,
             "the upload broke off after " + std::to_string(sink_->received()) + " of " +
                 std::to_string(entry_->size) + " bytes: " + ec.message(),
             false);
        return;
    }
    if (exchange_->stopping()) {
        fail(protocol::ErrorCode::interrupted, "the provider is stopping", false);
        return;
    }
    read();
}

void Upload::finish() {
    std::string stored;
    try {
        stored = sink_->store(entry_->name);
    } catch (const UploadError& e) {
        fail(e.code(), e.what(), true);
        return;
    }
    sink_.reset();
    const bool keep_alive = parser_->get().keep_alive();
    const UploadEntry entry = std::move(*entry_);
    entry_.reset();
    parser_.reset();
    chunk_ = {};
    const protocol::Message done = puts_.upload_done(entry, stored);
    exchange_->restart_timeout();
    exchange_->answer_json(200, keep_alive && !exchange_->stopping(), encode_reply(done));
}

void Upload::fail(protocol::ErrorCode code, const std::string& message, bool answer) {
    sink_.reset();  // the temporary file goes with it
    parser_.reset();
    chunk_ = {};
    if (!entry_) return;
    const protocol::Error error = puts_.upload_failed(*entry_, code, message);
    entry_.reset();
    if (!answer) {
        exchange_->drop();
        return;
    }
    const auto status = code == protocol::ErrorCode::too_large  ? http::status::payload_too_large
                        : code == protocol::ErrorCode::internal ? http::status::internal_server_error
                                                                : http::status::bad_request;
    exchange_->answer_error(status, false, error);
}

}  // namespace

void serve_upload(HttpExchange& exchange, http::request_parser<http::empty_body>&& header, PutDesk& puts) {
    const auto& req = header.get();
    const beast::string_view target = req.target();
    if (req.method() != http::verb::put) {
        exchange.answer_error(http::status::method_not_allowed, false, protocol::ErrorCode::bad_request,
                              "an upload is a PUT", "PUT");
        return;
    }
    // The link is used up by this request, whatever follows.
    auto entry = puts.take_upload(std::string_view(target.data(), target.size()));
    if (!entry) {
        exchange.answer_error(http::status::not_found, false, protocol::ErrorCode::not_found,
                              "unknown, used or expired upload link");
        return;
    }
    const std::int64_t size = entry->size;
    const auto length = header.content_length();
    if (!length || header.chunked()) {
        const std::string why = "an upload needs a Content-Length of " + std::to_string(size);
        puts.upload_failed(*entry, protocol::ErrorCode::interrupted, why);
        exchange.answer_error(http::status::length_required, false, protocol::ErrorCode::bad_request, why);
        return;
    }
    if (*length != static_cast<std::uint64_t>(size)) {
        const std::string why = "the upload's Content-Length is " + std::to_string(*length) + ", the put's size " +
                                std::to_string(size);
        puts.upload_failed(*entry, protocol::ErrorCode::interrupted, why);
        exchange.answer_error(http::status::bad_request, false, protocol::ErrorCode::bad_request, why);
        return;
    }
    std::make_shared<Upload>(exchange.hold(), puts, std::move(*entry))->start(std::move(header));
}

}  // namespace umf::provider
