// The stream of one provider connection once TLS is up: what the server's
// sessions hand on to one another and what a route answers on.
#pragma once

#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/ssl/ssl_stream.hpp>

namespace umf::provider {

using TlsStream = boost::beast::ssl_stream<boost::beast::tcp_stream>;

}  // namespace umf::provider
