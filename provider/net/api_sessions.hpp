// The protocol over plain HTTPS requests (docs/PROTOCOL.md, "HTTPS
// transport"), for browsers that refuse wss: to a self-signed certificate:
// the table of its sessions, each with the Conversation a WebSocket
// connection would hold, its idle expiry, the messages waiting for it and
// the long poll waiting for them. Free of sockets: the connection
// (HttpConnection) parses the request, calls in here and writes the Reply; a
// long poll hands over a Waiter that is called at most once, from any thread.
#pragma once

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "provider/net/message_handler.hpp"

namespace umf::provider {

// The "closed" codes of the HTTPS transport: those of a WebSocket close.
inline constexpr int kClosedNormal = 1000;     // the requester closed it
inline constexpr int kClosedGoingAway = 1001;  // the provider stops
inline constexpr int kClosedPolicy = 1008;     // refused hello, unknown or expired session
inline constexpr int kClosedRestart = 1012;    // the screens changed since the welcome
inline constexpr int kClosedTryLater = 1013;   // too many sessions

// Session ids: 128 random bits as 32 lowercase hex digits.
inline constexpr std::size_t kApiSessionIdChars = 32;

struct ApiSessionOptions {
    std::size_t max_sessions = 256;
    // A session without any request for this long ends (an open poll keeps
    // it; the poll's end counts as a request).
    std::chrono::milliseconds idle_expiry{60'000};
    // How long a long poll is held before it is answered with no messages.
    std::chrono::milliseconds poll_timeout{25'000};
};

class ApiSessions : public std::enable_shared_from_this<ApiSessions> {
public:
    // What to answer: the HTTP status and the JSON body
    // {"session":..., "messages":[...], "closed":...}.
    struct Reply {
        int status = 200;
        std::string body;
        bool ended = false;  // the session ended with this reply (or never began)
    };
    // Called at most once with a poll's answer, from any thread; must not
    // block (a connection posts it to its strand).
    using Waiter = std::function<void(Reply)>;

    // Timers (expiry) run on `executor`. Subscribes to the handler's screen
    // changes, so open polls of sessions welcomed before hear of them at once.
    static std::shared_ptr<ApiSessions> create(boost::asio::any_io_executor executor,
                                               std::shared_ptr<const MessageHandler> handler,
                                               ApiSessionOptions options = {});
    ~ApiSessions();
    ApiSessions(const ApiSessions&) = delete;
    ApiSessions& operator=(const ApiSessions&) = delete;

    // POST /api/hello: `body` is a hello; a welcome makes a session.
    Reply hello(std::string_view body, const std::string& peer);
    // POST /api/session/ID: one requester message.
    Reply message(std::string_view id, std::string_view body);
    // POST /api/session/ID/close.
    Reply close(std::string_view id);

    // GET /api/session/ID/events. Either answered at once (`now`: unknown
    // session, one from before the screens changed, messages waiting) or
    // `waiter` is kept under `ticket` until something is pushed, the session
    // ends, or a newer poll of the same session takes over.
    struct PollStart {
        std::optional<Reply> now;
        std::uint64_t ticket = 0;
    };
    PollStart begin_poll(std::string_view id, Waiter waiter);
    // The poll's timer ran out: the answer (normally no messages), or nullopt
    // when the waiter was already taken and is being called.
    std::optional<Reply> end_poll(std::uint64_t ticket);
    // The client went away: the waiter is dropped, never called.
    void cancel_poll(std::uint64_t ticket);

    // Ends every session (their open polls hear 1001) and stops the expiry
    // timer, so the io_context can run out of work.
    void stop();

    std::size_t size() const;
    std::size_t polls_waiting() const;
    const ApiSessionOptions& options() const { return options_; }

private:
    struct Entry;
    ApiSessions(boost::asio::any_io_executor executor, std::shared_ptr<const MessageHandler> handler,
                ApiSessionOptions options);

    std::shared_ptr<Entry> find_locked(std::string_view id) const;
    // Takes the entry out of the table; its open poll hears of it, and its
    // conversation ends once no request uses it. Call without mutex_ held.
    void end(const std::shared_ptr<Entry>& entry, int code);
    // A message the conversation pushes (a put's later answers), for the next poll.
    void push(Entry& entry, std::string encoded_message);
    void screens_changed();
    void arm_expiry_locked();
    void sweep();

    boost::asio::any_io_executor executor_;
    std::shared_ptr<const MessageHandler> handler_;
    ApiSessionOptions options_;
    std::shared_ptr<void> screens_watch_;  // held: the handler calls screens_changed

    mutable std::mutex mutex_;
    std::vector<std::shared_ptr<Entry>> sessions_;
    std::size_t hellos_under_way_ = 0;  // places held for hellos being handled
    std::uint64_t next_ticket_ = 1;
    boost::asio::steady_timer expiry_timer_;
    bool expiry_armed_ = false;
    bool stopped_ = false;
};

// The JSON envelope of every /api/ answer: {"session":"...","messages":[...],"closed":N};
// session empty and closed 0 leave them out.
std::string api_body(const std::vector<std::string>& encoded_messages, const std::string& session = {},
                     int closed = 0);

}  // namespace umf::provider
