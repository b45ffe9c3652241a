// Whether a request's body can be delimited only one way (RFC 9112, 6.1 and
// 6.3). A request that says both Transfer-Encoding and Content-Length, names
// a coding other than a single "chunked", repeats Content-Length, or comes as
// HTTP/1.0 with Transfer-Encoding is one that a proxy in front of the
// provider could delimit differently, hiding a second request in the body;
// it is answered 400 and the connection closed, never served.
#pragma once

#include <boost/beast/http/fields.hpp>
#include <optional>
#include <string>

namespace umf::provider {

// Why the framing is ambiguous, in words for the answer; nullopt when it is
// not. `version` is the request's: 11 for HTTP/1.1, 10 for HTTP/1.0.
std::optional<std::string> ambiguous_framing(unsigned version, const boost::beast::http::fields& fields);

}  // namespace umf::provider
