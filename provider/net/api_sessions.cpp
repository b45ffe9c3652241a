#include "provider/net/api_sessions.hpp"

#include <openssl/crypto.h>
#include <openssl/rand.h>

#include <algorithm>
#include <exception>
#include <stdexcept>

#include "shared/protocol/messages.hpp"

namespace umf::provider {

namespace p = protocol;

namespace {

// Messages a session may have waiting for its next poll; older ones give way.
constexpr std::size_t kMaxWaitingMessages = 64;

std::string make_session_id() {
    unsigned char bytes[kApiSessionIdChars / 2];
    if (RAND_bytes(bytes, sizeof bytes) != 1) throw std::runtime_error("the random generator failed");
    static constexpr char kHex[] = "0123456789abcdef";
    std::string id;
    id.reserve(kApiSessionIdChars);
    for (unsigned char b : bytes) {
        id += kHex[b >> 4];
        id += kHex[b & 15];
    }
    return id;
}

ApiSessions::Reply unknown_session() {
    return {404,
            api_body({p::encode(p::Error{std::nullopt, p::ErrorCode::not_found, "unknown or expired session"})}, {},
                     kClosedPolicy),
            true};
}

int closed_code(Answer::Then then) { return then == Answer::Then::restart ? kClosedRestart : kClosedPolicy; }

ApiSessions::Reply closed_reply(std::vector<std::string> messages, int code) {
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

struct ApiSessions::Entry {
    std::string id;                // the bearer secret; never logged
    std::uint64_t generation = 0;  // the screens its welcome described

    std::mutex conversation_mutex;  // one request at a time (taken before ApiSessions::mutex_)
    // The session ends with the entry: when the table has let it go and no
    // request is using it any more.
    std::unique_ptr<Conversation> conversation;

    // Guarded by ApiSessions::mutex_.
    std::chrono::steady_clock::time_point last_seen{};
    int requests_under_way = 0;
    bool ended = false;
    std::deque<std::string> waiting;  // encoded messages for the next poll
    Waiter waiter;
    std::uint64_t waiter_ticket = 0;
};

std::shared_ptr<ApiSessions> ApiSessions::create(boost::asio::any_io_executor executor,
                                                 std::shared_ptr<const MessageHandler> handler,
                                                 ApiSessionOptions options) {
    std::shared_ptr<ApiSessions> sessions(new ApiSessions(std::move(executor), std::move(handler), options));
    sessions->screens_watch_ = sessions->handler_->watch_screens([weak = std::weak_ptr<ApiSessions>(sessions)] {
        if (auto self = weak.lock()) self->screens_changed();
    });
    return sessions;
}

ApiSessions::ApiSessions(boost::asio::any_io_executor executor, std::shared_ptr<const MessageHandler> handler,
                         ApiSessionOptions options)
    : executor_(std::move(executor)),
      handler_(std::move(handler)),
      options_(options),
      expiry_timer_(executor_) {}

ApiSessions::~ApiSessions() = default;

std::shared_ptr<ApiSessions::Entry> ApiSessions::find_locked(std::string_view id) const {
    // The id is a bearer secret: every session's is compared, each in
    // constant time, so the time taken says nothing about how close a guess came.
    if (id.size() != kApiSessionIdChars) return nullptr;
    std::shared_ptr<Entry> found;
    for (const auto& entry : sessions_)
        if (CRYPTO_memcmp(entry->id.data(), id.data(), kApiSessionIdChars) == 0) found = entry;
    return found;
}

ApiSessions::Reply ApiSessions::hello(std::string_view body, const std::string& peer) {
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
    Answer answer;
    try {
        // What the conversation pushes (a put's answer) waits for the session's poll.
        entry->conversation = handler_->open(
            peer, [weak = weak_from_this(), weak_entry = std::weak_ptr<Entry>(entry)](std::string message) {
                auto self = weak.lock();
                auto pushed_to = weak_entry.lock();
                if (self && pushed_to) self->push(*pushed_to, std::move(message));
            });
        answer = entry->conversation->text(body);
    } catch (...) {
        std::lock_guard lock(mutex_);
        --hellos_under_way_;
        throw;
    }

    std::unique_lock lock(mutex_);
    --hellos_under_way_;
    if (!entry->conversation->welcomed() || answer.then != Answer::Then::go_on)
        return closed_reply(std::move(answer.messages), closed_code(answer.then));
    std::vector<std::string> messages = std::move(answer.messages);
    entry->id = make_session_id();
    entry->generation = entry->conversation->screens_generation();
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

ApiSessions::Reply ApiSessions::message(std::string_view id, std::string_view body) {
    std::shared_ptr<Entry> entry;
    {
        std::lock_guard lock(mutex_);
        entry = find_locked(id);
        if (!entry) return unknown_session();
        entry->last_seen = std::chrono::steady_clock::now();
        ++entry->requests_under_way;
    }
    Answer answer;
    {
        std::lock_guard conversation_lock(entry->conversation_mutex);
        bool ended;
        {
            std::lock_guard lock(mutex_);
            ended = entry->ended;
        }
        if (!ended) {
            try {
                answer = entry->conversation->text(body);
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
    if (answer.then != Answer::Then::go_on) {
        const int code = closed_code(answer.then);
        end(entry, code);
        return closed_reply(std::move(answer.messages), code);
    }
    return {200, api_body(answer.messages), false};
}

ApiSessions::Reply ApiSessions::close(std::string_view id) {
    std::shared_ptr<Entry> entry;
    {
        std::lock_guard lock(mutex_);
        entry = find_locked(id);
        if (!entry) return unknown_session();
    }
    end(entry, kClosedNormal);
    return closed_reply({}, kClosedNormal);
}

ApiSessions::PollStart ApiSessions::begin_poll(std::string_view id, Waiter waiter) {
    const std::uint64_t generation = handler_->screens_generation();
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

std::optional<ApiSessions::Reply> ApiSessions::end_poll(std::uint64_t ticket) {
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

void ApiSessions::cancel_poll(std::uint64_t ticket) {
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

void ApiSessions::push(Entry& entry, std::string encoded_message) {
    Waiter waiter;
    std::vector<std::string> messages;
    {
        std::lock_guard lock(mutex_);
        // Pushed during the hello (before the table has it) or after the end: dropped.
        if (entry.ended || entry.id.empty()) return;
        entry.waiting.push_back(std::move(encoded_message));
        if (entry.waiting.size() > kMaxWaitingMessages) entry.waiting.pop_front();
        if (!entry.waiter) return;
        waiter = std::move(entry.waiter);
        entry.waiter = nullptr;
        entry.last_seen = std::chrono::steady_clock::now();
        messages.assign(entry.waiting.begin(), entry.waiting.end());
        entry.waiting.clear();
    }
    waiter(Reply{200, api_body(messages), false});
}

void ApiSessions::end(const std::shared_ptr<Entry>& entry, int code) {
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
}

void ApiSessions::screens_changed() {
    const std::uint64_t generation = handler_->screens_generation();
    std::vector<std::shared_ptr<Entry>> stale;
    {
        std::lock_guard lock(mutex_);
        for (const auto& entry : sessions_)
            if (entry->waiter && entry->generation != generation) stale.push_back(entry);
    }
    // Those without an open poll hear it at their next request.
    for (const auto& entry : stale) end(entry, kClosedRestart);
}

void ApiSessions::arm_expiry_locked() {
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

void ApiSessions::sweep() {
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

void ApiSessions::stop() {
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

std::size_t ApiSessions::size() const {
    std::lock_guard lock(mutex_);
    return sessions_.size();
}

std::size_t ApiSessions::polls_waiting() const {
    std::lock_guard lock(mutex_);
    return static_cast<std::size_t>(
        std::count_if(sessions_.begin(), sessions_.end(), [](const auto& entry) { return bool(entry->waiter); }));
}

}  // namespace umf::provider
