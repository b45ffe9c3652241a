// The PutDeciders that need no window (put_decision.hpp): a fixed answer
// (`--puts always|never`), the answers given through the control socket
// (`umf-provider puts`, for headless screens, kiosks and scripts), and the
// first answer of several (the desktop prompt and the control socket), which
// takes the others' questions back.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "provider/put/put_decision.hpp"

namespace umf::provider {

// Answers every offer at once, from within ask, with the same answer:
// save for `--puts always`, dismiss for `--puts never`.
class FixedPutDecider : public PutDecider {
public:
    explicit FixedPutDecider(PutAnswer answer) : answer_(answer) {}
    void ask(const PutOffer& offer, std::function<void(PutReply)> answer) override;
    void withdraw(std::uint64_t) override {}

private:
    PutAnswer answer_;
};

// Keeps the offers until answer() (the control socket's put_answer) or
// withdraw(). Thread-safe.
class ControlPutDecider : public PutDecider {
public:
    struct Pending {
        PutOffer offer;
        std::chrono::steady_clock::duration age{};
    };

    void ask(const PutOffer& offer, std::function<void(PutReply)> answer) override;
    void withdraw(std::uint64_t id) override;

    // The offers waiting, oldest first.
    std::vector<Pending> pending() const;
    // Answers offer `id` and forgets it; the offer answered, or nullopt when
    // none is waiting with that id (never was, answered already, withdrawn).
    std::optional<PutOffer> answer(std::uint64_t id, PutReply reply);

private:
    struct Entry {
        PutOffer offer;
        std::function<void(PutReply)> answer;
        std::chrono::steady_clock::time_point since;
    };
    mutable std::mutex mutex_;
    std::map<std::uint64_t, Entry> entries_;  // ids grow, so this is oldest first
};

// Offers each put to every decider, in order; the first answer wins and is
// passed on, the others are withdrawn and their later answers ignored.
// withdraw() reaches all. A decider that answers within ask (FixedPutDecider)
// leaves the later ones unasked.
class FirstAnswerDecider : public PutDecider {
public:
    explicit FirstAnswerDecider(std::vector<std::shared_ptr<PutDecider>> deciders);
    void ask(const PutOffer& offer, std::function<void(PutReply)> answer) override;
    void withdraw(std::uint64_t id) override;

private:
    std::vector<std::shared_ptr<PutDecider>> deciders_;
};

const char* to_string(PutAnswer answer);
std::optional<PutAnswer> put_answer_from_string(const std::string& name);

}  // namespace umf::provider
