// The body of a large upload read past the TLS stream's per-record
// machinery, the way content/direct_file_send.hpp sends a large download:
// OpenSSL reads up to 256 KiB of records from the socket per call (a
// socket BIO in place of the stream's, read-ahead on) and decrypts them
// into pieces of 1 MiB, and the reactor is asked only when the socket is
// empty. Through the stream every 16 KiB
// record took a composed operation of its own, and the provider's one thread
// spent four seconds of CPU per GB receiving.
//
// It can only start where the stream holds nothing of the body yet: the
// client asked "Expect: 100-continue" and has waited for the answer
// (direct_receive_possible says so); a browser's body, which follows its
// header at once, goes through the stream. The stream's own read side comes
// back when the body is in (the answer is written through the stream; the
// connection then ends).
#pragma once

#include <boost/beast/core/error.hpp>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "provider/net/http_exchange.hpp"

namespace umf::provider {

// True when nothing of the request's body has been read through the stream:
// no decrypted bytes in the exchange's buffer or in TLS, no ciphertext in the
// stream's BIO. Call after "100 Continue" went out and before any read.
bool direct_receive_possible(HttpExchange& exchange);

// Reads `length` bytes of body from the connection and hands them to `take`
// in order (false from it stops the reading: the route has ended the
// upload). `done` hears, on the connection's strand, success or why the
// connection broke, ended or went quiet for `idle`; after success the
// stream is whole again for the answer.
void receive_body_direct(std::shared_ptr<HttpExchange> exchange, std::uint64_t length, std::chrono::seconds idle,
                         std::function<bool(const char* data, std::size_t size)> take,
                         std::function<void(boost::beast::error_code)> done);

}  // namespace umf::provider
