#include "provider/content/download_route.hpp"

#include <boost/beast/core/string.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>
#include <cctype>
#include <chrono>
#include <memory>
#include <string>
#include <tuple>
#include <utility>

#include "provider/common/secret_compare.hpp"
#include "provider/content/direct_file_send.hpp"
#include "provider/content/resume_range.hpp"
#include "provider/content/verified_file_body.hpp"
#include "provider/net/http_response_headers.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;

namespace {

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

// Ends a transfer's checkout when the last holder lets go: complete when the
// whole body went out, else the link stays for the rest to be asked for.
struct CheckoutEnd {
    DownloadTable& downloads;
    DownloadCheckout checkout;
    bool complete = false;
    ~CheckoutEnd() { downloads.end(checkout, complete); }
};

// File bodies from this size on are sent by send_file_direct.
constexpr std::uint64_t kDirectSendBytes = 1 << 20;

std::string_view header_text(const HttpRequest& req, http::field field) {
    const beast::string_view value = req[field];
    return {value.data(), value.size()};
}

// The token of "Authorization: Bearer TOKEN" (the scheme in any case);
// empty when there is none.
std::string_view bearer_token(const HttpRequest& req) {
    std::string_view value = header_text(req, http::field::authorization);
    constexpr std::string_view kScheme = "bearer ";
    if (value.size() <= kScheme.size() ||
        !beast::iequals(beast::string_view(value.data(), kScheme.size()), beast::string_view(kScheme.data(), kScheme.size())))
        return {};
    value.remove_prefix(kScheme.size());
    while (!value.empty() && value.front() == ' ') value.remove_prefix(1);
    return value;
}

}  // namespace

void serve_download(HttpExchange& exchange, const HttpRequest& req, DownloadTable& downloads,
                    std::function<void(const std::filesystem::path&)> forget_file) {
    const bool keep_alive = req.keep_alive();
    const beast::string_view target = req.target();
    auto checkout = downloads.begin(std::string_view(target.data(), target.size()));
    if (!checkout) {
        exchange.answer_error(http::status::not_found, keep_alive, protocol::ErrorCode::not_found,
                              "unknown, finished or expired download link");
        return;
    }
    auto end = std::make_shared<CheckoutEnd>(CheckoutEnd{downloads, *checkout});
    const DownloadEntry& entry = *checkout->entry;
    // Nothing of the link's file for a request without the grabbing
    // session's token; the link stays for its owner.
    if (!entry.token.empty() && !tokens_equal(bearer_token(req), entry.token)) {
        exchange.answer_error(http::status::unauthorized, keep_alive, protocol::ErrorCode::unauthorized,
                              "a download link is used with the pairing token of the session that grabbed it "
                              "(Authorization: Bearer TOKEN)");
        return;
    }
    const bool head = req.method() == http::verb::head;
    const auto size = static_cast<std::uint64_t>(entry.size);
    const std::string etag = entry.sha256.empty() ? std::string() : download_etag(entry.sha256);
    const ResumeRange range =
        etag.empty() ? ResumeRange{}
                     : resume_range(header_text(req, http::field::range), header_text(req, http::field::if_range), etag,
                                    size);
    if (range.kind == ResumeRange::Kind::unsatisfiable) {
        auto res = std::make_shared<http::response<http::empty_body>>(http::status::range_not_satisfiable, req.version());
        set_common_headers(*res);
        res->set(http::field::content_range, "bytes */" + std::to_string(size));
        res->keep_alive(keep_alive);
        res->content_length(0);
        write_response(exchange, std::move(res));
        return;
    }
    const std::uint64_t offset = range.kind == ResumeRange::Kind::rest ? range.offset : 0;
    auto prepare = [&](auto& res) {
        set_common_headers(res);
        if (range.kind == ResumeRange::Kind::rest) {
            res.result(http::status::partial_content);
            res.set(http::field::content_range,
                    "bytes " + std::to_string(offset) + "-" + std::to_string(size - 1) + "/" + std::to_string(size));
        }
        res.set(http::field::content_type, entry.mime);
        res.set(http::field::content_disposition, content_disposition(entry.name));
        res.set(http::field::cache_control, "no-store");
        if (!etag.empty()) {
            res.set(http::field::etag, etag);
            res.set(http::field::accept_ranges, "bytes");
        }
        res.keep_alive(keep_alive);
        res.content_length(size - offset);
    };
    // A slow reader gets a minute plus a second per megabyte.
    beast::get_lowest_layer(exchange.stream()).expires_after(std::chrono::seconds(60 + (size - offset) / (1 << 20)));
    if (entry.bytes) {
        auto res = std::make_shared<http::response<http::string_body>>(http::status::ok, req.version());
        if (!head) res->body() = entry.bytes->substr(static_cast<std::size_t>(offset));
        prepare(*res);
        auto& r = *res;
        send_response(exchange.stream(), r,
                      [held = exchange.hold(), res = std::move(res), keep_alive, end, head](beast::error_code ec) {
                          if (ec) return;
                          end->complete = !head;
                          held->written(keep_alive);
                      });
        return;
    }
    VerifiedFileBody::value_type body;
    if (const auto why = body.open(*entry.file, entry.identity, entry.sha256, offset, checkout->checkpoints,
                                   entry.leased_ctime_ns)) {
        // Gone or changed since the grab: what would arrive is not what the
        // content message promised.
        exchange.answer_error(http::status::conflict, keep_alive, protocol::ErrorCode::internal, *why);
        return;
    }
    if (head) {
        auto res = std::make_shared<http::response<http::empty_body>>(http::status::ok, req.version());
        prepare(*res);
        write_response(exchange, std::move(res));
        return;
    }
    if (size - offset >= kDirectSendBytes) {
        // A large body goes out past the stream's per-record machinery
        // (direct_file_send.hpp); the connection ends with it.
        auto res = std::make_shared<http::response<http::empty_body>>(http::status::ok, req.version());
        prepare(*res);
        res->keep_alive(false);
        auto& r = *res;
        const auto idle = std::chrono::seconds(60);
        send_response(exchange.stream(), r,
                      [held = exchange.hold(), res = std::move(res),
                       body = std::make_shared<VerifiedFileBody::value_type>(std::move(body)), file = *entry.file, end,
                       forget_file = std::move(forget_file), idle](beast::error_code ec) mutable {
                          if (ec) return;
                          send_file_direct(held, std::move(*body), idle,
                                           [file, end, forget_file](beast::error_code sent) {
                                               // A cut body: the next grab hashes the file again.
                                               if (sent == DownloadCheck::changed) forget_file(file);
                                               end->complete = !sent;
                                           });
                      });
        return;
    }
    auto res = std::make_shared<http::response<VerifiedFileBody>>(
        std::piecewise_construct, std::make_tuple(std::move(body)), std::make_tuple(http::status::ok, req.version()));
    prepare(*res);
    auto& r = *res;
    http::async_write(exchange.stream(), r,
                      [held = exchange.hold(), res = std::move(res), keep_alive, file = *entry.file, end,
                       forget_file = std::move(forget_file)](beast::error_code ec, std::size_t) {
                          if (ec == DownloadCheck::changed) {
                              // Cut short: the phone sees fewer bytes than promised
                              // and keeps none; the next grab hashes the file again.
                              forget_file(file);
                              held->drop();
                              return;
                          }
                          if (ec) return;
                          end->complete = true;
                          held->written(keep_alive);
                      });
}

}  // namespace umf::provider
