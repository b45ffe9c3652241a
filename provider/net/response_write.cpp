#include "provider/net/response_write.hpp"

#include <boost/beast/http/write.hpp>
#include <utility>

namespace umf::provider {

namespace http = boost::beast::http;

namespace {

template <class Body>
void write(TlsStream& stream, http::response<Body>& response, ResponseSent sent) {
    http::async_write(stream, response,
                      [sent = std::move(sent)](boost::beast::error_code ec, std::size_t) { sent(ec); });
}

}  // namespace

void send_response(TlsStream& stream, http::response<http::string_body>& response, ResponseSent sent) {
    write(stream, response, std::move(sent));
}

void send_response(TlsStream& stream, http::response<http::empty_body>& response, ResponseSent sent) {
    write(stream, response, std::move(sent));
}

}  // namespace umf::provider
