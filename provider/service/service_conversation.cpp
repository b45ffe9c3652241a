// A requester session as the transport holds it: the service's SessionState
// and the replies encoded. The session ends with the conversation.
#include <memory>
#include <utility>

#include "provider/common/encode_reply.hpp"
#include "provider/service/service.hpp"

namespace umf::provider {

namespace {

class ServiceConversation : public Conversation {
public:
    ServiceConversation(std::shared_ptr<const Service> service, std::string peer, Push push)
        : service_(std::move(service)) {
        state_.peer = std::move(peer);
        state_.outbox = [push = std::move(push)](std::uint64_t, std::string message) { push(std::move(message)); };
    }
    ~ServiceConversation() override { service_->session_ended(state_); }
    ServiceConversation(const ServiceConversation&) = delete;
    ServiceConversation& operator=(const ServiceConversation&) = delete;

    Answer text(std::string_view message) override { return answer(service_->handle_text(state_, message)); }
    Answer binary() override { return answer(service_->handle_binary(state_)); }
    bool welcomed() const override { return state_.welcomed; }
    std::uint64_t screens_generation() const override { return state_.screens_generation; }

private:
    static Answer answer(const Replies& replies) {
        Answer out;
        for (const auto& reply : replies.replies) out.messages.push_back(encode_reply(reply));
        if (replies.close) out.then = replies.restart ? Answer::Then::restart : Answer::Then::close;
        return out;
    }

    std::shared_ptr<const Service> service_;
    SessionState state_;
};

}  // namespace

std::unique_ptr<Conversation> Service::open(std::string peer, Push push) const {
    return std::make_unique<ServiceConversation>(shared_from_this(), std::move(peer), std::move(push));
}

std::size_t Service::max_message_bytes() const {
    return static_cast<std::size_t>(config_.limits.max_message_bytes);
}

}  // namespace umf::provider
