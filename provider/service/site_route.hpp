// The web client's routes: its files, held in memory (static_site.hpp), with
// the Content-Security-Policy its page runs under; and its share target,
// which a share reaches only when the page's service worker did not take it.
#pragma once

#include "provider/net/http_exchange.hpp"
#include "provider/service/static_site.hpp"

namespace umf::provider {

// The web client's share target (its manifest).
inline constexpr const char* kSharePath = "/share";

// GET or HEAD of any other path: the file, or 404.
void serve_site(HttpExchange& exchange, const HttpRequest& req, const StaticSite& site);
// POST /share: sent back to the page, which says to open it once first. The
// body (the shared files) is not read: the connection closes after the answer.
void answer_share(HttpExchange& exchange);

}  // namespace umf::provider
