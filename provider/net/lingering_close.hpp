// The end of a connection after an error answer (or a WebSocket close such as
// 1009): closing a socket with unread bytes makes the kernel send a reset,
// which can destroy the answer before the peer reads it, so a sender still
// writing what was refused would never see why. Instead our FIN goes out (no
// TLS close_notify: the peer may be mid-record) and what still comes is read
// and dropped until the peer closes, for at most 5 s or 64 MiB.
#pragma once

#include <boost/beast/core/tcp_stream.hpp>
#include <memory>

namespace umf::provider {

// Closes `stream` so; `owner` (the session that holds it) is kept alive
// until then.
void lingering_close(boost::beast::tcp_stream& stream, std::shared_ptr<void> owner);

}  // namespace umf::provider
