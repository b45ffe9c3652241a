// PUT /up/<link> (docs/PROTOCOL.md, "Upload"): the body is the put's file
// from byte Upload-Offset (absent: 0), which must be what the provider holds
// (else 409: the requester asks again), to its end (Content-Length, not
// chunked); it streams to the link's UploadSink in 64 KiB pieces and is
// answered with the put's `done`. HEAD /up/<link> says how much is held
// (Upload-Offset, Upload-Length). A connection that breaks leaves the bytes
// with the link for the rest (upload_table.hpp); a failed upload (no room,
// another hash) removes its file and tells the put's session, answered while
// the connection is there.
#pragma once

#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/parser.hpp>

#include "provider/net/http_exchange.hpp"
#include "provider/put/put_desk.hpp"

namespace umf::provider {

// Takes the request once its header is read; the body is still unread.
void serve_upload(HttpExchange& exchange, boost::beast::http::request_parser<boost::beast::http::empty_body>&& header,
                  PutDesk& puts);

}  // namespace umf::provider
