// The headers every response of the provider carries (downloads, the web
// client's files, the HTTPS transport, error answers).
#pragma once

#include <boost/beast/http/field.hpp>
#include <boost/beast/http/message.hpp>

namespace umf::provider {

template <class Body>
void set_common_headers(boost::beast::http::response<Body>& res) {
    res.set(boost::beast::http::field::server, "umf-provider");
    res.set("X-Content-Type-Options", "nosniff");
    res.set("Referrer-Policy", "no-referrer");
}

}  // namespace umf::provider
