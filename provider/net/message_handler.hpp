// What the transport asks of the layer above it (the service): a
// conversation per requester session, whatever carries it (a WebSocket or
// the HTTPS transport's requests), and the few facts a connection needs. The
// transport knows messages only as encoded text; what they mean is the
// handler's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace umf::provider {

// What one received message gets: the messages to send back, in order, and
// what then becomes of the session.
struct Answer {
    std::vector<std::string> messages;  // encoded
    enum class Then {
        go_on,
        close,    // refused (a WebSocket closes with 1008)
        restart,  // its welcome no longer describes the screens (1012): the requester connects again
    } then = Then::go_on;
};

// Where a conversation's own later messages go (a put's answer): called from
// any thread with an encoded message; must not block.
using Push = std::function<void(std::string encoded_message)>;

// One requester session from its hello on. It ends when destroyed: the
// transport drops it when the session closes, welcomed or not. The transport
// calls one method at a time.
class Conversation {
public:
    virtual ~Conversation() = default;
    virtual Answer text(std::string_view message) = 0;
    virtual Answer binary() = 0;
    // Welcomed: the hello was taken.
    virtual bool welcomed() const = 0;
    // The screens generation its welcome described (MessageHandler::screens_generation).
    virtual std::uint64_t screens_generation() const = 0;
};

class MessageHandler {
public:
    virtual ~MessageHandler() = default;
    // A new session from `peer` (the remote address: limits on wrong tokens
    // are per address); `push` is where its later messages go.
    virtual std::unique_ptr<Conversation> open(std::string peer, Push push) const = 0;
    // Counts the changes of the screens (one came, went or changed size).
    virtual std::uint64_t screens_generation() const = 0;
    // Calls `on_change` after each change of the screens (from any thread)
    // for as long as the returned handle is held; it must not block.
    virtual std::shared_ptr<void> watch_screens(std::function<void()> on_change) const = 0;
    // A larger message is refused (a WebSocket closes with 1009).
    virtual std::size_t max_message_bytes() const = 0;
};

}  // namespace umf::provider
