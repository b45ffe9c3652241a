#include "provider/put/put_desk.hpp"

#include <cstdio>
#include <exception>
#include <vector>

#include "provider/common/encode_reply.hpp"
#include "provider/put/desktop_open.hpp"
#include "provider/put/put_deciders.hpp"
#include "provider/put/upload_sink.hpp"

namespace umf::provider {

namespace p = protocol;
using Clock = std::chrono::steady_clock;

namespace {

std::string seconds_text(std::chrono::milliseconds ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", static_cast<double>(ms.count()) / 1000.0);
    return text;
}

}  // namespace

std::shared_ptr<PutDesk> PutDesk::create(std::shared_ptr<PutDecider> decider, PutSettings settings,
                                         std::shared_ptr<ActivityListener> activity) {
    return std::shared_ptr<PutDesk>(new PutDesk(std::move(decider), std::move(settings), std::move(activity)));
}

PutDesk::PutDesk(std::shared_ptr<PutDecider> decider, PutSettings settings, std::shared_ptr<ActivityListener> activity)
    : decider_(std::move(decider)),
      settings_(std::move(settings)),
      trusted_(settings_.trusted_devices),
      uploads_(settings_.upload_ttl),
      activity_(std::move(activity)) {}

PutActivity PutDesk::activity_of(const PutOffer& offer, std::uint64_t session, PutStage stage) {
    PutActivity a;
    a.session = session;
    a.stage = stage;
    a.kind = offer.kind;
    a.name = offer.kind == p::ContentKind::url ? offer.title : offer.name;
    a.url = offer.url;
    a.size = offer.size;
    a.client = offer.client;
    a.device = offer.device;
    return a;
}

void PutDesk::report(const PutOffer& offer, std::uint64_t session, PutStage stage, std::string detail,
                     bool asked) const {
    if (!activity_) return;
    PutActivity a = activity_of(offer, session, stage);
    a.detail = std::move(detail);
    a.asked = asked;
    activity_->put(a);
}

void PutDesk::report(const UploadEntry& entry, PutStage stage, std::string path, std::string detail) const {
    if (!activity_) return;
    PutActivity a;
    a.session = entry.session;
    a.stage = stage;
    a.kind = p::ContentKind::file;
    a.name = entry.name;
    a.size = entry.size;
    a.path = std::move(path);
    a.detail = std::move(detail);
    activity_->put(a);
}

std::optional<WindowPlacement> PutDesk::placement(const std::optional<ScreenPoint>& at) const {
    if (!at || !screen_rects_) return std::nullopt;
    const auto screen = screen_rects_(at->screen);
    if (!screen) return std::nullopt;
    return WindowPlacement{at->root_x, at->root_y, *screen};
}

std::unique_ptr<NewWindowWatch> PutDesk::window_watch(const std::optional<ScreenPoint>& at) const {
    // The windows are noted now, before the opener starts, so its window is the one that is new.
    const auto where = placement(at);
    if (!where || !settings_.watch_new_window) return nullptr;
    return settings_.watch_new_window(*where);
}

PutDesk::~PutDesk() { stop(); }

void PutDesk::stop() {
    std::vector<std::uint64_t> withdrawn;
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        for (const auto& [id, pending] : pending_) withdrawn.push_back(id);
        pending_.clear();
    }
    wake_.notify_all();
    if (watcher_.joinable() && watcher_.get_id() != std::this_thread::get_id()) watcher_.join();
    if (decider_)
        for (std::uint64_t id : withdrawn) decider_->withdraw(id);
}

std::size_t PutDesk::offers_waiting() const {
    std::lock_guard lock(mutex_);
    return pending_.size();
}

void PutDesk::attach(std::uint64_t session, Outbox outbox) {
    if (!outbox) return;
    std::lock_guard lock(outbox_mutex_);
    outboxes_[session] = std::move(outbox);
}

bool PutDesk::push(std::uint64_t session, const p::Message& message) {
    Outbox outbox;
    {
        std::lock_guard lock(outbox_mutex_);
        const auto it = outboxes_.find(session);
        if (it == outboxes_.end()) return false;
        outbox = it->second;
    }
    outbox(encode_reply(message));
    return true;
}

void PutDesk::session_ended(std::uint64_t session) {
    {
        std::lock_guard lock(outbox_mutex_);
        outboxes_.erase(session);
    }
    std::vector<Pending> withdrawn;
    {
        std::lock_guard lock(mutex_);
        for (auto it = pending_.begin(); it != pending_.end();) {
            if (it->second.session == session) {
                withdrawn.push_back(std::move(it->second));
                it = pending_.erase(it);
            } else {
                ++it;
            }
        }
    }
    for (const Pending& pending : withdrawn) {
        decider_->withdraw(pending.offer.id);
        report(pending.offer, pending.session, PutStage::withdrawn);
    }
}

p::Message PutDesk::offer(const PutRequester& who, const p::Put& put, std::optional<ScreenPoint> at) {
    if (!decider_) return p::Error{put.id, p::ErrorCode::refused, "this provider takes no puts"};
    Pending pending;
    pending.session = who.session;
    pending.id = put.id;
    PutOffer& offer = pending.offer;
    offer.client = who.client;
    offer.device = who.device;
    offer.kind = put.kind;
    offer.title = put.title;
    offer.at = at;
    if (put.kind == p::ContentKind::url) {
        if (!put.url) return p::Error{put.id, p::ErrorCode::bad_request, "a url put needs \"url\""};
        offer.url = *put.url;
    } else if (put.kind == p::ContentKind::file) {
        if (!put.name || !put.mime || !put.size)
            return p::Error{put.id, p::ErrorCode::bad_request, "a file put needs name, mime and size"};
        offer.name = p::safe_file_name(*put.name);
        offer.mime = *put.mime;
        offer.size = *put.size;
        pending.sha256 = put.sha256.value_or("");  // empty: the upload names it after the bytes
        // Before anyone is asked: a file that cannot land is refused now.
        const auto refuse = [&](p::ErrorCode code, std::string why) -> p::Message {
            report(offer, who.session, PutStage::refused, why, false);
            return p::Error{put.id, code, std::move(why)};
        };
        if (offer.size > settings_.max_bytes)
            return refuse(p::ErrorCode::too_large, offer.name + " is " + std::to_string(offer.size) +
                                                       " bytes, more than the limit of " +
                                                       std::to_string(settings_.max_bytes));
        std::error_code ec;
        std::filesystem::create_directories(settings_.folder, ec);
        const auto room = free_bytes(settings_.folder);
        if (!room) return refuse(p::ErrorCode::internal, "the provider cannot use its put folder");
        if (static_cast<std::uintmax_t>(offer.size) > *room)
            return refuse(p::ErrorCode::too_large, offer.name + " is " + std::to_string(offer.size) +
                                                       " bytes; the provider's folder has " + std::to_string(*room) +
                                                       " bytes free");
    } else {
        return p::Error{put.id, p::ErrorCode::bad_request, "a put is a url or a file"};
    }

    {
        std::lock_guard lock(mutex_);
        if (stopping_) return p::Error{put.id, p::ErrorCode::refused, "the provider is stopping"};
        offer.id = next_offer_++;
    }
    // A trusted device's files do what was chosen with "always"; its URLs open.
    if (const auto files = trusted_.files_answer(offer.device)) return act(pending, PutReply{*files, false}, Via::trusted);

    const std::uint64_t id = offer.id;
    {
        std::lock_guard lock(mutex_);
        pending.deadline = Clock::now() + settings_.answer_timeout;
        pending.in_ask = true;
        pending_.emplace(id, pending);
        start_watch_locked();
    }
    std::weak_ptr<PutDesk> weak = weak_from_this();
    try {
        decider_->ask(offer, [weak, id](PutReply reply) {
            if (auto self = weak.lock()) self->answered(id, reply);
        });
    } catch (const std::exception& e) {
        std::lock_guard lock(mutex_);
        pending_.erase(id);
        report(offer, who.session, PutStage::failed, std::string("the screen cannot ask: ") + e.what(), false);
        return p::Error{put.id, p::ErrorCode::internal, std::string("the screen cannot ask: ") + e.what()};
    }
    std::optional<PutReply> early;
    {
        std::lock_guard lock(mutex_);
        const auto it = pending_.find(id);
        if (it != pending_.end()) {
            it->second.in_ask = false;
            early = it->second.early;
            if (early)
                pending_.erase(it);
            else
                // Under the lock: an answer from another thread waits for
                // this line, so the console never tells the answer first.
                report(offer, who.session, PutStage::asking);
        }
    }
    wake_.notify_all();
    // Answered before ask returned (a fixed policy): the answer is the reply
    // itself, so it cannot overtake an "asking".
    if (early) return act(pending, *early, Via::at_once);
    return p::PutStatus{put.id, p::PutState::asking, std::nullopt, std::nullopt, std::nullopt};
}

void PutDesk::answered(std::uint64_t offer, PutReply reply) {
    Pending pending;
    {
        std::lock_guard lock(mutex_);
        const auto it = pending_.find(offer);
        if (it == pending_.end()) return;  // withdrawn, timed out, or answered before
        if (it->second.in_ask) {
            if (!it->second.early) it->second.early = reply;
            return;
        }
        pending = std::move(it->second);
        pending_.erase(it);
    }
    push(pending.session, act(pending, reply, Via::asked));
}

p::Message PutDesk::act(const Pending& pending, const PutReply& reply, Via via) {
    const PutOffer& offer = pending.offer;
    const bool asked = via == Via::asked;
    if (reply.answer == PutAnswer::dismiss) {
        report(offer, pending.session, PutStage::refused, asked ? "declined at the screen" : "the provider takes no puts",
               asked);
        return p::Error{pending.id, p::ErrorCode::refused, "the person at the screen declined it"};
    }
    const bool url = offer.kind == p::ContentKind::url;
    const bool always = reply.always_from_device && !offer.device.empty();
    // A URL's "always" says nothing of files: a known device keeps its choice.
    if (always) trusted_.add(offer.device, url ? std::nullopt : std::optional<PutAnswer>(reply.answer));
    if (activity_) {
        PutActivity a = activity_of(offer, pending.session, PutStage::accepted);
        a.answer = url ? "open" : to_string(reply.answer);
        a.asked = asked;
        a.trusted = via == Via::trusted;
        a.always = always;
        activity_->put(a);
    }
    if (url) {
        std::string problem;
        const bool in_place = offer.at && settings_.open_url_at && settings_.open_url_at(*offer.at, offer.url);
        if (!in_place && !open_with_desktop(offer.url, &problem, window_watch(offer.at))) {
            report(offer, pending.session, PutStage::failed, problem);
            return p::Error{pending.id, p::ErrorCode::internal, problem};
        }
        report(offer, pending.session, PutStage::opened);
        return p::PutStatus{pending.id, p::PutState::done, std::nullopt, p::PutOutcome::opened, std::nullopt};
    }
    UploadEntry entry;
    entry.session = pending.session;
    entry.id = pending.id;
    entry.offer = offer.id;
    entry.name = offer.name;
    entry.mime = offer.mime;
    entry.size = offer.size;
    entry.sha256 = pending.sha256;
    entry.open = reply.answer == PutAnswer::open;
    entry.folder = settings_.folder;
    entry.at = offer.at;
    std::string link;
    try {
        link = uploads_.add(std::move(entry));
    } catch (const std::exception& e) {
        report(offer, pending.session, PutStage::failed, e.what());
        return p::Error{pending.id, p::ErrorCode::internal, e.what()};
    }
    return p::PutStatus{pending.id, p::PutState::upload, link, std::nullopt, std::nullopt};
}

std::optional<UploadCheckout> PutDesk::begin_upload(std::string_view target) { return uploads_.begin(target); }

std::shared_ptr<UploadSink> PutDesk::keep_upload_sink(const UploadCheckout& checkout, std::shared_ptr<UploadSink> sink) {
    return uploads_.keep_sink(checkout, std::move(sink));
}

void PutDesk::end_upload(const UploadCheckout& checkout, UploadEnd how) {
    uploads_.end(checkout, how);
    if (how != UploadEnd::broken) return;
    // The watch tells the session if nobody goes on with it in time.
    std::lock_guard lock(mutex_);
    start_watch_locked();
    wake_.notify_all();
}

p::Message PutDesk::upload_done(const UploadEntry& entry, const std::string& stored_name) {
    p::PutStatus done{entry.id, p::PutState::done, std::nullopt, p::PutOutcome::saved, stored_name};
    const std::string path = (entry.folder / stored_name).string();
    if (entry.open && open_with_desktop(path, nullptr, window_watch(entry.at))) done.outcome = p::PutOutcome::opened;
    report(entry, done.outcome == p::PutOutcome::opened ? PutStage::opened : PutStage::stored, path);
    push(entry.session, done);
    return done;
}

p::Error PutDesk::upload_failed(const UploadEntry& entry, p::ErrorCode code, const std::string& message) {
    p::Error error{entry.id, code, message};
    report(entry, PutStage::failed, {}, p::to_string(code) + std::string(": ") + message);
    push(entry.session, error);
    return error;
}

void PutDesk::start_watch_locked() {
    if (watcher_.joinable() || stopping_) return;
    watcher_ = std::thread([this] { watch_deadlines(); });
}

void PutDesk::watch_deadlines() {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
        std::optional<Clock::time_point> next = uploads_.next_abandon();
        for (const auto& [id, pending] : pending_)
            if (!pending.in_ask && (!next || pending.deadline < *next)) next = pending.deadline;
        if (next)
            wake_.wait_until(lock, *next);
        else
            wake_.wait(lock);
        if (stopping_) break;
        const auto now = Clock::now();
        std::vector<Pending> expired;
        for (auto it = pending_.begin(); it != pending_.end();) {
            if (!it->second.in_ask && it->second.deadline <= now) {
                expired.push_back(std::move(it->second));
                it = pending_.erase(it);
            } else {
                ++it;
            }
        }
        const auto abandoned = uploads_.take_abandoned(now);
        if (expired.empty() && abandoned.empty()) continue;
        lock.unlock();
        for (const AbandonedUpload& a : abandoned)
            upload_failed(a.entry, p::ErrorCode::interrupted,
                          "the upload broke off after " + std::to_string(a.received) + " of " +
                              std::to_string(a.entry.size) + " bytes and was not resumed within " +
                              seconds_text(uploads_.ttl()));
        for (const Pending& pending : expired) {
            decider_->withdraw(pending.offer.id);
            report(pending.offer, pending.session, PutStage::timed_out,
                   "no answer within " + seconds_text(settings_.answer_timeout));
            push(pending.session, p::Error{pending.id, p::ErrorCode::refused,
                                           "no answer at the screen within " + seconds_text(settings_.answer_timeout)});
        }
        lock.lock();
    }
}

}  // namespace umf::provider
