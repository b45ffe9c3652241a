// Writing a response on a connection's stream, for the connection and for
// every route. Beast's composed write over TLS is compiled anew for each
// completion handler type, seconds of compiling each time, so the handler is
// type-erased and each body's write is compiled once, in response_write.cpp.
// Like any handler on the stream, `sent` runs on the connection's strand.
#pragma once

#include <boost/beast/core/error.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <functional>

#include "provider/net/tls_stream.hpp"

namespace umf::provider {

// Called once the whole response is out, or with the error that ended it.
using ResponseSent = std::function<void(boost::beast::error_code)>;

// `response` must outlive the write: `sent` usually holds it.
void send_response(TlsStream& stream, boost::beast::http::response<boost::beast::http::string_body>& response,
                   ResponseSent sent);
void send_response(TlsStream& stream, boost::beast::http::response<boost::beast::http::empty_body>& response,
                   ResponseSent sent);

}  // namespace umf::provider
