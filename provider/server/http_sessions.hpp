// The protocol over plain HTTPS requests (docs/PROTOCOL.md, "HTTPS
// transport"), for browsers that refuse wss: to a self-signed certificate:
// the table of HTTP sessions, each with the SessionState a WebSocket
// connection would hold, its idle expiry, the messages waiting for it and
// the long poll waiting for them. Free of sockets: the connection (HttpSession)
// parses the request, calls in here and writes the Reply; a long poll hands
// over a Waiter that is called at most once, from any thread.
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

#include "common/encode_reply.hpp"
#include "server/service.hpp"

namespace umf::provider {

// The "closed" codes of the HTTPS transport: those of a WebSocket close.
inline constexpr int kClosedNormal = 1000;     // the requester closed it
inline constexpr int kClosedGoingAway = 1001;  // the provider stops
inline constexpr int kClosedPolicy = 1008;     // refused hello, unknown or expired session
inline constexpr int kClosedRestart = 1012;    // the screens changed since the welcome
inline constexpr int kClosedTryLater = 1013;   // too many sessions

// Session ids: 128 random bits as 32 lowercase hex digits.
inline constexpr std::size_t kHttpSessionIdChars = 32;

struct HttpSessionOptions {
    std::size_t max_sessions = 256;
    // A session without any request for this long ends (an open poll keeps
    // it; the poll's end counts as a request).
    std::chrono::milliseconds idle_expiry{60'000};
    // How long a long poll is held before it is answered with no messages.
    std::chrono::milliseconds poll_timeout{25'000};
};

class HttpSessions : public std::enable_shared_from_this<HttpSessions> {
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

    // Timers (expiry) run on `executor`. Subscribes to the service's screen
    // changes, so open polls of sessions welcomed before hear of them at once.
    static std::shared_ptr<HttpSessions> create(boost::asio::any_io_executor executor,
                                                std::shared_ptr<const Service> service,
                                                HttpSessionOptions options = {});
    ~HttpSessions();
    HttpSessions(const HttpSessions&) = delete;
    HttpSessions& operator=(const HttpSessions&) = delete;

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

    // A message for one session (by the number its welcome gave it,
    // SessionState::id), delivered to its poll; false when there is no such
    // session. A put's later answers (put_status, refused, interrupted) come
    // this way: each session's SessionState::outbox calls it.
    bool push(std::uint64_t session, std::string encoded_message);

    // Ends every session (their open polls hear 1001) and stops the expiry
    // timer, so the io_context can run out of work.
    void stop();

    std::size_t size() const;
    std::size_t polls_waiting() const;
    const HttpSessionOptions& options() const { return options_; }

private:
    struct Entry;
    HttpSessions(boost::asio::any_io_executor executor, std::shared_ptr<const Service> service,
                 HttpSessionOptions options);

    std::shared_ptr<Entry> find_locked(std::string_view id) const;
    // Takes the entry out of the table; its open poll and the activity
    // listener hear of it. Call without mutex_ held.
    void end(const std::shared_ptr<Entry>& entry, int code);
    void screens_changed();
    void arm_expiry_locked();
    void sweep();

    boost::asio::any_io_executor executor_;
    std::shared_ptr<const Service> service_;
    HttpSessionOptions options_;
    std::shared_ptr<void> screens_watch_;  // held: the service calls screens_changed

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
