// Which part of a download a request asks for (RFC 9110, Range and
// If-Range). A requester whose download broke off asks for the rest, from
// the first byte it lacks to the end; the download answers 206 with that.
// Ranges that end before the file does, and several ranges, are answered
// with the whole file (a server may ignore Range), since the whole file's
// SHA-256 is checked only at its end.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace umf::provider {

struct ResumeRange {
    enum class Kind { whole, rest, unsatisfiable } kind = Kind::whole;
    std::uint64_t offset = 0;  // the first byte sent (rest)
};

// The download's validator: strong, from the SHA-256 it announced.
std::string download_etag(std::string_view sha256);

// `range` and `if_range` as the request has them (empty when absent),
// against a file of `size` bytes whose validator is `etag`. A Range whose
// If-Range names another validator gets the whole file.
ResumeRange resume_range(std::string_view range, std::string_view if_range, std::string_view etag, std::uint64_t size);

}  // namespace umf::provider
