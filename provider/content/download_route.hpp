// GET or HEAD /dl/<link> (docs/PROTOCOL.md, "Downloads"), with the
// grabbing session's pairing token as a bearer token (401 without): the whole file
// (200), or with Range (and If-Range naming its ETag, "sha256-<hex>") the
// rest from where a broken download stopped (206); the link ends when a GET
// of it completes (download_table.hpp). Bytes the provider made are sent as
// they are; a file is sent only while it is the one announced (the same
// identity before the first byte, the same SHA-256 before the last piece:
// verified_file_body.hpp), else the response is cut short.
#pragma once

#include <filesystem>
#include <functional>

#include "provider/content/download_table.hpp"
#include "provider/net/http_exchange.hpp"

namespace umf::provider {

// `forget_file` hears of a file found changed while it was sent, so that its
// next grab hashes it again.
void serve_download(HttpExchange& exchange, const HttpRequest& req, DownloadTable& downloads,
                    std::function<void(const std::filesystem::path&)> forget_file);

}  // namespace umf::provider
