// GET or HEAD /dl/<link> (docs/PROTOCOL.md, "Downloads"): the link is used up
// by the request, whatever follows. Bytes the provider made are sent as they
// are; a file is sent only while it is the one announced (the same identity
// before the first byte, the same SHA-256 before the last piece:
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
