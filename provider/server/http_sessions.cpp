#include "server/http_sessions.hpp"

#include <openssl/crypto.h>
#include <openssl/rand.h>

#include <algorithm>
#include <exception>
#include <stdexcept>

namespace umf::provider {

namespace p = protocol;

namespace {

// Messages a session may have waiting for its next poll; older ones give way.
constexpr std::size_t kMaxWaitingMessages = 64;

std::string make_session_id() {
    unsigned char bytes[kHttpSessionIdChars / 2];
    if (RAND_bytes(bytes, sizeof bytes) != 1) throw std::runtime_error("the random generator failed");
    static constexpr char kHex[] = "0123456789abcdef";
    std::string id;
    id.reserve(kHttpSessionIdChars);
    for (unsigned char b : bytes) {
        id += kHex[b >> 4];
        id += kHex[b & 15];
    }
    return id;
}

HttpSessions::Reply unknown_session() {
    return {404,
            api_body({p::encode(p::Error{std::nullopt, p::ErrorCode::not_found, "unknown or expired session"})}, {},
                     kClosedPolicy),
            true};
}

HttpSessions::Reply closed_reply(std::vector<std::string> messages, int code) {
    return {200, api_body(messages, {}, code), true};
}

}  // namespace

std::string api_body(const std::vector<std::string>& encoded_messages, const std::string& session, int closed) {
    std::string body = "{";
    if (!session.empty()) body += "\"session\":\"" + session + "\",";
    body += "\"messages\":[";
    for (std::size_t i = 0; i < encoded_messages.size(); ++i) {
        if (i) body += ',';
        body += encoded_messages[i];
    }
    body += ']';
    if (closed) body += ",\"closed\":" + std::to_string(closed);
    body += '}';
    return body;
}

struct HttpSessions::Entry {
    std::string id;            // the bearer secret; never logged
    std::uint64_t number = 0;  // SessionState::id, for the activity listener and push
    std::uint64_t generation = 0;  // the screens its welcome described

    std::mutex state_mutex;  // one request at a time on the state (taken before HttpSessions::mutex_)
    SessionState state;

    // Guarded by HttpSessions::mutex_.
    SteadyTime last_seen{};
    int requests_under_way = 0;
    bool ended = false;
    std::deque<std::string> waiting;  // encoded messages for the next poll
    Waiter waiter;
    std::uint64_t waiter_ticket = 0;
};

std::shared_ptr<HttpSessions> HttpSessions::create(boost::asio::any_io_executor executor,
                                                   std::shared_ptr<const Service> service, HttpSessionOptions options) {
    std::shared_ptr<HttpSessions> sessions(new HttpSessions(std::move(executor), std::move(service), options));
    sessions->screens_watch_ = sessions->service_->watch_screens([weak = std::weak_ptr<HttpSessions>(sessions)] {
        if (auto self = weak.lock()) self->screens_changed();
    });
    return sessions;
}

HttpSessions::HttpSessions(boost::asio::any_io_executor executor, std::shared_ptr<const Service> service,
                           HttpSessionOptions options)
    : executor_(std::move(executor)),
      service_(std::move(service)),
      options_(options),
      expiry_timer_(executor_) {}

HttpSessions::~HttpSessions() = default;

std::shared_ptr<HttpSessions::Entry> HttpSessions::find_locked(std::string_view id) const {
    // The id is a bearer secret: every session's is compared, each in
    // constant time, so the time taken says nothing about how close a guess came.
    if (id.size() != kHttpSessionIdChars) return nullptr;
    std::shared_ptr<Entry> found;
    for (const auto& entry : sessions_)
        if (CRYPTO_memcmp(entry->id.data(), id.data(), kHttpSessionIdChars) == 0) found = entry;
    return found;
}

HttpSessions::Reply HttpSessions::hello(std::string_view body, const std::string& peer) {
    {
        std::lock_guard lock(mutex_);
        if (stopped_ || sessions_.size() + hellos_under_way_ >= options_.max_sessions) {
            const std::string text = stopped_ ? "the provider is stopping"
                                              : "the provider has " + std::to_string(options_.max_sessions) +
                                                    " HTTPS sessions open, its limit; try again later";
            return {503, api_body({p::encode(p::Error{std::nullopt, p::ErrorCode::rate_limited, text})}, {}, kClosedTryLater),
                    true};
        }
        ++hellos_under_way_;
    }
    auto entry = std::make_shared<Entry>();
    entry->state.peer = peer;
    // What the service pushes to the session (a put's answer) waits for its poll.
    entry->state.outbox = [weak = weak_from_this()](std::uint64_t session, std::string message) {
        if (auto self = weak.lock()) self->push(session, std::move(message));
    };
    Replies out;
    try {
        out = service_->handle_text(entry->state, body);
    } catch (...) {
        std::lock_guard lock(mutex_);
        --hellos_under_way_;
        throw;
    }
    std::vector<std::string> messages;
    for (const auto& reply : out.replies) messages.push_back(encode_reply(reply));

    std::unique_lock lock(mutex_);
    --hellos_under_way_;
    if (!entry->state.welcomed || out.close)
        return closed_reply(std::move(messages), out.restart ? kClosedRestart : kClosedPolicy);
    entry->id = make_session_id();
    entry->number = entry->state.id;
    entry->generation = entry->state.screens_generation;
    entry->last_seen = std::chrono::steady_clock::now();
    if (stopped_) {
        // Welcomed while the server stopped: it ends at once.
        lock.unlock();
        end(entry, kClosedGoingAway);
        return closed_reply(std::move(messages), kClosedGoingAway);
    }
    sessions_.push_back(entry);
    arm_expiry_locked();
    return {200, api_body(messages, entry->id), false};
}

HttpSessions::Reply HttpSessions::message(std::string_view id, std::string_view body) {
    std::shared_ptr<Entry> entry;
    {
        std::lock_guard lock(mutex_);
        entry = find_locked(id);
        if (!entry) return unknown_session();
        entry->last_seen = std::chrono::steady_clock::now();
        ++entry->requests_under_way;
    }
    Replies out;
    {
        std::lock_guard state_lock(entry->state_mutex);
        bool ended;
        {
            std::lock_guard lock(mutex_);
            ended = entry->ended;
        }
        if (!ended) {
            try {
                out = service_->handle_text(entry->state, body);
            } catch (...) {
                std::lock_guard lock(mutex_);
                --entry->requests_under_way;
                throw;
            }
        }
        std::lock_guard lock(mutex_);
        --entry->requests_under_way;
        entry->last_seen = std::chrono::steady_clock::now();
        if (ended) return unknown_session();
    }
    std::vector<std::string> messages;
    for (const auto& reply : out.replies) messages.push_back(encode_reply(reply));
    if (out.close) {
        const int code = out.restart ? kClosedRestart : kClosedPolicy;
        end(entry, code);
        return closed_reply(std::move(messages), code);
    }
    return {200, api_body(messages), false};
}

HttpSessions::Reply HttpSessions::close(std::string_view id) {
    std::shared_ptr<Entry> entry;
    {
        std::lock_guard lock(mutex_);
        entry = find_locked(id);
        if (!entry) return unknown_session();
    }
    end(entry, kClosedNormal);
    return closed_reply({}, kClosedNormal);
}

HttpSessions::PollStart HttpSessions::begin_poll(std::string_view id, Waiter waiter) {
    const std::uint64_t generation = service_->screens()->generation;
    std::shared_ptr<Entry> entry;
    Waiter replaced;
    PollStart start;
    {
        std::lock_guard lock(mutex_);
        entry = find_locked(id);
        if (!entry) return {unknown_session(), 0};
        entry->last_seen = std::chrono::steady_clock::now();
        if (entry->generation == generation) {
            if (!entry->waiting.empty()) {
                std::vector<std::string> messages(entry->waiting.begin(), entry->waiting.end());
                entry->waiting.clear();
                return {Reply{200, api_body(messages), false}, 0};
            }
            // A newer poll of the same session takes over from an older one,
            // which is answered with nothing.
            replaced = std::move(entry->waiter);
            start.ticket = next_ticket_++;
            entry->waiter = std::move(waiter);
            entry->waiter_ticket = start.ticket;
        }
    }
    if (!start.ticket) {
        // Welcomed before the screens changed: told to connect again.
        end(entry, kClosedRestart);
        return {closed_reply({}, kClosedRestart), 0};
    }
    if (replaced) replaced(Reply{200, api_body({}), false});
    return start;
}

std::optional<HttpSessions::Reply> HttpSessions::end_poll(std::uint64_t ticket) {
    std::lock_guard lock(mutex_);
    for (const auto& entry : sessions_) {
        if (!entry->waiter || entry->waiter_ticket != ticket) continue;
        entry->waiter = nullptr;
        entry->last_seen = std::chrono::steady_clock::now();
        std::vector<std::string> messages(entry->waiting.begin(), entry->waiting.end());
        entry->waiting.clear();
        return Reply{200, api_body(messages), false};
    }
    return std::nullopt;
}

void HttpSessions::cancel_poll(std::uint64_t ticket) {
    Waiter dropped;  // destroyed outside the lock
    std::lock_guard lock(mutex_);
    for (const auto& entry : sessions_) {
        if (!entry->waiter || entry->waiter_ticket != ticket) continue;
        dropped = std::move(entry->waiter);
        entry->waiter = nullptr;
        // The expiry counts from here: a phone whose connection dropped
        // comes back with a new poll or not at all.
        entry->last_seen = std::chrono::steady_clock::now();
        return;
    }
}

bool HttpSessions::push(std::uint64_t session, std::string encoded_message) {
    Waiter waiter;
    std::vector<std::string> messages;
    {
        std::lock_guard lock(mutex_);
        const auto it = std::find_if(sessions_.begin(), sessions_.end(),
                                     [&](const auto& entry) { return entry->number == session; });
        if (it == sessions_.end()) return false;
        Entry& entry = **it;
        entry.waiting.push_back(std::move(encoded_message));
        if (entry.waiting.size() > kMaxWaitingMessages) entry.waiting.pop_front();
        if (!entry.waiter) return true;
        waiter = std::move(entry.waiter);
        entry.waiter = nullptr;
        entry.last_seen = std::chrono::steady_clock::now();
        messages.assign(entry.waiting.begin(), entry.waiting.end());
        entry.waiting.clear();
    }
    waiter(Reply{200, api_body(messages), false});
    return true;
}

void HttpSessions::end(const std::shared_ptr<Entry>& entry, int code) {
    Waiter waiter;
    std::vector<std::string> messages;
    {
        std::lock_guard lock(mutex_);
        if (entry->ended) return;
        entry->ended = true;
        std::erase(sessions_, entry);
        waiter = std::move(entry->waiter);
        entry->waiter = nullptr;
        messages.assign(entry->waiting.begin(), entry->waiting.end());
        entry->waiting.clear();
    }
    if (waiter) waiter(closed_reply(std::move(messages), code));
    SessionState ended;
    ended.welcomed = true;
    ended.id = entry->number;
    service_->session_ended(ended);
}

void HttpSessions::screens_changed() {
    const std::uint64_t generation = service_->screens()->generation;
    std::vector<std::shared_ptr<Entry>> stale;
    {
        std::lock_guard lock(mutex_);
        for (const auto& entry : sessions_)
            if (entry->waiter && entry->generation != generation) stale.push_back(entry);
    }
    // Those without an open poll hear it at their next request.
    for (const auto& entry : stale) end(entry, kClosedRestart);
}

void HttpSessions::arm_expiry_locked() {
    if (expiry_armed_ || stopped_ || sessions_.empty()) return;
    expiry_armed_ = true;
    const auto period = std::clamp<std::chrono::milliseconds>(options_.idle_expiry / 4, std::chrono::milliseconds(10),
                                                              std::chrono::milliseconds(5000));
    expiry_timer_.expires_after(period);
    expiry_timer_.async_wait([weak = weak_from_this()](boost::system::error_code ec) {
        if (ec) return;
        if (auto self = weak.lock()) self->sweep();
    });
}

void HttpSessions::sweep() {
    std::vector<std::shared_ptr<Entry>> expired;
    {
        std::lock_guard lock(mutex_);
        expiry_armed_ = false;
        if (stopped_) return;
        const auto now = std::chrono::steady_clock::now();
        for (const auto& entry : sessions_)
            if (!entry->waiter && entry->requests_under_way == 0 && now - entry->last_seen >= options_.idle_expiry)
                expired.push_back(entry);
    }
    for (const auto& entry : expired) end(entry, kClosedPolicy);
    std::lock_guard lock(mutex_);
    arm_expiry_locked();
}

void HttpSessions::stop() {
    std::vector<std::shared_ptr<Entry>> all;
    {
        std::lock_guard lock(mutex_);
        if (stopped_) return;
        stopped_ = true;
        expiry_timer_.cancel();
        all = sessions_;
    }
    for (const auto& entry : all) end(entry, kClosedGoingAway);
}

std::size_t HttpSessions::size() const {
    std::lock_guard lock(mutex_);
    return sessions_.size();
}

std::size_t HttpSessions::polls_waiting() const {
    std::lock_guard lock(mutex_);
    return static_cast<std::size_t>(
        std::count_if(sessions_.begin(), sessions_.end(), [](const auto& entry) { return bool(entry->waiter); }));
}

}  // namespace umf::provider
