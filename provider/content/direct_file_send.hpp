// The body of a large file download, encrypted and sent without the
// asynchronous TLS stream's per-record machinery. Through the stream, each
// 16 KiB record costs a composed operation, a copy through a BIO pair and a
// socket write of its own; here OpenSSL writes the records into a memory
// buffer and the socket takes a quarter of a megabyte per send, waiting on
// the reactor only when the socket is full. The file is read and hashed on
// a thread beside it (verified_file_reader.hpp), with VerifiedFileBody's
// checks (same identity, same SHA-256 before the last piece). The stream's
// TLS state is the stream's no more afterwards: the connection ends with
// the body (the response says "Connection: close").
#pragma once

#include <boost/beast/core/error.hpp>
#include <functional>
#include <memory>

#include "provider/content/verified_file_body.hpp"
#include "provider/net/http_exchange.hpp"

namespace umf::provider {

// Sends `body` (opened) on `exchange`'s connection, whose response header
// has been written; then the connection is dropped. `done` hears how it
// ended on the connection's strand: success, DownloadCheck::changed (the
// file's bytes were not the announced ones: the body was cut short), or why
// the connection broke or went quiet for `idle`.
void send_file_direct(std::shared_ptr<HttpExchange> exchange, VerifiedFileBody::value_type body,
                      std::chrono::seconds idle, std::function<void(boost::beast::error_code)> done);

}  // namespace umf::provider
