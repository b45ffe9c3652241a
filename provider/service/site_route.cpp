#include "provider/service/site_route.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "provider/net/http_response_headers.hpp"

namespace umf::provider {

namespace beast = boost::beast;
namespace http = beast::http;

namespace {

constexpr const char* kShareUnavailable = "/?share=unavailable";

// For the web client's files: a page that runs WebAssembly in a module worker
// and talks to its own origin over https: and wss:. 'self' covers wss: to the
// same host and port only in browsers that follow CSP Level 3 on this point,
// so the WebSocket's own origin is named as well, from the Host header the
// page was loaded with (when it is a plain host[:port]). A page opened by
// address also asks the screen's .local name whether it answers there
// (web/site/screen_name.js), and a page pointed at another screen fetches
// the fields of the screens nearby (web/site/nearby.js), so https: to .local
// names on any port is allowed too, and no further.
std::string content_security_policy(beast::string_view host) {
    std::string connect = "'self'";
    const bool plain_host = !host.empty() && host.size() <= 262 &&
                            std::all_of(host.begin(), host.end(), [](char c) {
                                return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ||
                                       c == ':' || c == '[' || c == ']';
                            });
    if (plain_host) connect += " wss://" + std::string(host);
    connect += " https://*.local:*";
    return "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self' blob:; connect-src " +
           connect +
           "; img-src 'self' blob: data:; media-src 'self' blob:; style-src 'self'; object-src 'none'; "
           "base-uri 'none'; frame-ancestors 'none'; form-action 'self'";
}

}  // namespace

void serve_site(HttpExchange& exchange, const HttpRequest& req, const StaticSite& site) {
    const bool keep_alive = req.keep_alive();
    const beast::string_view target = req.target();
    const auto file = site.find(std::string_view(target.data(), target.size()));
    if (!file) {
        exchange.answer_error(http::status::not_found, keep_alive, protocol::ErrorCode::not_found, "no such page");
        return;
    }
    auto res = std::make_shared<http::response<http::string_body>>(http::status::ok, req.version());
    set_common_headers(*res);
    res->set(http::field::content_type, file->mime);
    res->set(http::field::cache_control, "no-cache");
    if (!file->download_name.empty())
        res->set(http::field::content_disposition, "attachment; filename=\"" + file->download_name + "\"");
    res->set("Content-Security-Policy", content_security_policy(req[http::field::host]));
    res->keep_alive(keep_alive);
    if (req.method() == http::verb::get) res->body() = *file->bytes;
    res->prepare_payload();
    if (req.method() == http::verb::head) res->content_length(file->bytes->size());
    write_response(exchange, std::move(res));
}

void answer_share(HttpExchange& exchange) {
    auto res = std::make_shared<http::response<http::string_body>>(http::status::see_other, 11);
    res->set(http::field::server, "umf-provider");
    res->set(http::field::location, kShareUnavailable);
    res->set(http::field::cache_control, "no-store");
    res->set("Referrer-Policy", "no-referrer");
    res->keep_alive(false);
    res->prepare_payload();
    exchange.restart_timeout();
    write_response(exchange, std::move(res));
}

}  // namespace umf::provider
