// PUT /up/<link> (docs/PROTOCOL.md, "Upload"): the link is used up by the
// request, whatever follows. The body must be as long as the accepted put
// says (Content-Length, not chunked); it streams to an UploadSink in 64 KiB
// pieces and is answered with the put's `done`. A failed upload removes its
// file and tells the put's session; an answer is sent while the connection is
// there, and the connection then ends. An upload torn down unfinished (the
// server stopping) tells the put's session as well.
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
