#include "provider/net/http_framing.hpp"

#include <boost/beast/core/string.hpp>

namespace umf::provider {

namespace http = boost::beast::http;

namespace {

boost::beast::string_view trimmed(boost::beast::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

// Every coding of every Transfer-Encoding line is exactly one "chunked".
bool only_chunked(const http::fields& fields) {
    int codings = 0;
    bool chunked = true;
    for (const auto& f : fields) {
        if (f.name() != http::field::transfer_encoding) continue;
        boost::beast::string_view rest = f.value();
        for (;;) {
            const auto comma = rest.find(',');
            const auto coding = trimmed(rest.substr(0, comma));
            // Empty list elements are allowed and mean nothing (RFC 9110, 5.6.1).
            if (!coding.empty()) {
                ++codings;
                chunked = chunked && boost::beast::iequals(coding, "chunked");
            }
            if (comma == boost::beast::string_view::npos) break;
            rest = rest.substr(comma + 1);
        }
    }
    return codings == 1 && chunked;
}

}  // namespace

std::optional<std::string> ambiguous_framing(unsigned version, const http::fields& fields) {
    const auto encodings = fields.count(http::field::transfer_encoding);
    const auto lengths = fields.count(http::field::content_length);
    if (encodings > 0 && lengths > 0) return "a request with both Transfer-Encoding and Content-Length";
    if (lengths > 1) return "a request with more than one Content-Length";
    if (encodings > 0 && version < 11) return "Transfer-Encoding in an HTTP/1.0 request";
    if (encodings > 0 && !only_chunked(fields))
        return "a Transfer-Encoding other than chunked (the only coding taken here)";
    return std::nullopt;
}

}  // namespace umf::provider
