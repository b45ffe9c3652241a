#include "provider/put/put_deciders.hpp"

namespace umf::provider {

void FixedPutDecider::ask(const PutOffer&, std::function<void(PutReply)> answer) {
    if (answer) answer(PutReply{answer_, false});
}

void ControlPutDecider::ask(const PutOffer& offer, std::function<void(PutReply)> answer) {
    std::lock_guard lock(mutex_);
    entries_[offer.id] = Entry{offer, std::move(answer), std::chrono::steady_clock::now()};
}

void ControlPutDecider::withdraw(std::uint64_t id) {
    std::function<void(PutReply)> dropped;  // destroyed outside the lock
    std::lock_guard lock(mutex_);
    if (auto it = entries_.find(id); it != entries_.end()) {
        dropped = std::move(it->second.answer);
        entries_.erase(it);
    }
}

std::vector<ControlPutDecider::Pending> ControlPutDecider::pending() const {
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    std::vector<Pending> out;
    out.reserve(entries_.size());
    for (const auto& [id, entry] : entries_) out.push_back({entry.offer, now - entry.since});
    return out;
}

std::optional<PutOffer> ControlPutDecider::answer(std::uint64_t id, PutReply reply) {
    Entry entry;
    {
        std::lock_guard lock(mutex_);
        auto it = entries_.find(id);
        if (it == entries_.end()) return std::nullopt;
        entry = std::move(it->second);
        entries_.erase(it);
    }
    // Outside the lock: the answer may withdraw (FirstAnswerDecider) or ask again.
    if (entry.answer) entry.answer(reply);
    return std::move(entry.offer);
}

namespace {

// One offer's race among the deciders.
struct Race {
    std::mutex mutex;
    bool done = false;
    std::size_t winner = 0;
    std::function<void(PutReply)> answer;
};

}  // namespace

FirstAnswerDecider::FirstAnswerDecider(std::vector<std::shared_ptr<PutDecider>> deciders)
    : deciders_(std::move(deciders)) {}

void FirstAnswerDecider::ask(const PutOffer& offer, std::function<void(PutReply)> answer) {
    auto race = std::make_shared<Race>();
    race->answer = std::move(answer);
    const std::uint64_t id = offer.id;
    // The callbacks reach the other deciders without keeping them (a decider
    // holding its own callback would keep itself alive), and without this
    // object, which may be gone when an answer comes.
    std::vector<std::weak_ptr<PutDecider>> others(deciders_.begin(), deciders_.end());
    const auto& deciders = deciders_;
    for (std::size_t i = 0; i < deciders.size(); ++i) {
        {
            std::lock_guard lock(race->mutex);
            if (race->done) break;  // answered already, within an earlier ask
        }
        deciders[i]->ask(offer, [race, others, i, id](PutReply reply) {
            std::function<void(PutReply)> pass_on;
            {
                std::lock_guard lock(race->mutex);
                if (race->done) return;
                race->done = true;
                race->winner = i;
                pass_on = std::move(race->answer);
            }
            for (std::size_t j = 0; j < others.size(); ++j)
                if (j != i)
                    if (auto d = others[j].lock()) d->withdraw(id);
            if (pass_on) pass_on(reply);
        });
    }
    // An answer that came on another thread while later deciders were still
    // being asked withdrew them possibly before they were asked: again now.
    std::size_t winner = 0;
    {
        std::lock_guard lock(race->mutex);
        if (!race->done) return;
        winner = race->winner;
    }
    for (std::size_t j = 0; j < deciders.size(); ++j)
        if (j != winner) deciders[j]->withdraw(id);
}

void FirstAnswerDecider::withdraw(std::uint64_t id) {
    for (const auto& d : deciders_) d->withdraw(id);
}

const char* to_string(PutAnswer answer) {
    switch (answer) {
        case PutAnswer::save: return "save";
        case PutAnswer::open: return "open";
        case PutAnswer::dismiss: return "dismiss";
    }
    return "dismiss";
}

std::optional<PutAnswer> put_answer_from_string(const std::string& name) {
    if (name == "save") return PutAnswer::save;
    if (name == "open") return PutAnswer::open;
    if (name == "dismiss") return PutAnswer::dismiss;
    return std::nullopt;
}

}  // namespace umf::provider
