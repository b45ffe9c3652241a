#include "shared/requester_core/pointer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shared/aiming/aim.hpp"
#include "shared/protocol/media_types.hpp"

namespace umf::requester_core {

namespace p = protocol;

namespace {

bool usable(const p::FieldPoint& point) { return aiming::usable_point({point.u, point.v}); }

double distance(const p::FieldPoint& a, const p::FieldPoint& b) { return std::hypot(a.u - b.u, a.v - b.v); }

void append(Step& into, Step from) {
    for (auto& m : from.send) into.send.push_back(std::move(m));
    if (from.download) into.download = std::move(from.download);
    if (from.upload) into.upload = std::move(from.upload);
    into.reconnect = into.reconnect || from.reconnect;
    if (from.notice) into.notice = std::move(from.notice);
}

bool http_url(const std::string& url) { return p::is_http_url(url) && url.size() <= p::kMaxUrlBytes; }

}  // namespace

const char* to_string(Phase phase) {
    switch (phase) {
        case Phase::searching: return "searching";
        case Phase::locked: return "locked";
        case Phase::grabbing: return "grabbing";
        case Phase::receiving: return "receiving";
        case Phase::putting: return "putting";
        case Phase::result: return "result";
        case Phase::failed: return "failed";
    }
    return "failed";
}

const char* to_string(PutProgress progress) {
    switch (progress) {
        case PutProgress::none: return "none";
        case PutProgress::hashing: return "hashing";
        case PutProgress::sending: return "sending";
        case PutProgress::asking: return "asking";
        case PutProgress::uploading: return "uploading";
        case PutProgress::confirming: return "confirming";
    }
    return "none";
}

Pointer::Pointer(const p::Welcome& welcome, Timing timing, bool auto_act) : timing_(timing), auto_act_(auto_act) {
    // The welcome's limit covers aims and seeking together; aims go at
    // most max_aims_per_s even when the provider takes more.
    const double limit = std::max(welcome.limits.aims_per_s, 0.1);
    aim_interval_s_ = 1.0 / std::min(limit, timing_.max_aims_per_s);
    timing_.seeking_interval_s = std::max(timing_.seeking_interval_s, 1.0 / limit);
}

p::RequestId Pointer::next_id() { return p::RequestId{next_++}; }

Step Pointer::frame(double t, const Sighting& s) {
    Step step = tick(t);
    if (!started_) {
        started_ = true;
        searching_since_ = t;
    }
    if (view_.phase != Phase::searching && view_.phase != Phase::locked) return step;  // a sheet has the user
    see_another_field(t, s);
    if (s.locked && usable(s.point)) {
        if (view_.phase == Phase::searching) {
            view_.phase = Phase::locked;
            view_.hint = false;
            steady_frames_ = 0;
        }
        if (steady_frames_ == 0 || distance(s.point, anchor_) > timing_.steady_modules) {
            anchor_ = s.point;
            steady_since_ = t;
            steady_frames_ = 1;
        } else {
            ++steady_frames_;
        }
        view_.aim = s.point;
        view_.steady = t - steady_since_ >= timing_.steady_s && steady_frames_ >= timing_.steady_min_frames;
        if (!last_aim_ || t - *last_aim_ >= aim_interval_s_) {
            step.send.push_back(p::Aim{next_id(), s.point, std::clamp(s.confidence, 0.0, 1.0)});
            last_aim_ = t;
        }
        if (auto_act_ && view_.steady) append(step, tap(t));
        return step;
    }
    if (view_.phase == Phase::locked) {
        view_.phase = Phase::searching;
        searching_since_ = t;
        view_.target_kind.reset();
        view_.target_title.clear();
    }
    steady_frames_ = 0;
    view_.aim.reset();
    view_.steady = false;
    view_.hint = t - searching_since_ > timing_.hint_after_s;
    if (!last_seeking_ || t - *last_seeking_ >= timing_.seeking_interval_s) {
        step.send.push_back(p::Seeking{});
        last_seeking_ = t;
    }
    return step;
}

void Pointer::see_another_field(double t, const Sighting& s) {
    const bool here = s.another_field && !(s.locked && usable(s.point));
    if (here) {
        if (!another_since_ || t - *another_last_ > timing_.another_gap_s) another_since_ = t;
        another_last_ = t;
    } else if (another_last_ && (s.locked || t - *another_last_ > timing_.another_gap_s)) {
        another_since_.reset();
        another_last_.reset();
    }
    view_.another_screen = another_since_ && *another_last_ - *another_since_ >= timing_.another_screen_s;
}

Step Pointer::tap(double t) {
    if (view_.phase != Phase::locked || !view_.aim) return {};
    pending_point_ = *view_.aim;
    view_.target_kind.reset();
    if (view_.mode == Mode::grab) {
        pending_ = p::RequestId{"g" + std::to_string(next_++)};
        view_.phase = Phase::grabbing;
        deadline_ = t + timing_.grab_timeout_s;
        deadline_code_ = "unreachable";
        deadline_why_ = "the screen did not answer the grab";
        return {{p::Grab{*pending_, pending_point_}}};
    }
    pending_ = p::RequestId{"p" + std::to_string(next_++)};
    view_.phase = Phase::putting;
    if (item_->kind == p::ContentKind::file && !item_->sha256 && !item_->hash_after) {
        view_.put = PutProgress::hashing;  // hashed() sends it
        return {};
    }
    return send_put(t);
}

Step Pointer::hashed(double t, const std::string& sha256) {
    if (!item_ || item_->kind != p::ContentKind::file) return {};
    item_->sha256 = sha256;
    if (view_.phase == Phase::putting && view_.put == PutProgress::hashing) return send_put(t);
    return {};
}

Step Pointer::send_put(double t) {
    p::Put put;
    put.id = *pending_;
    put.point = pending_point_;
    put.kind = item_->kind;
    put.title = item_->title.substr(0, p::kMaxTitleBytes);
    if (item_->kind == p::ContentKind::url) {
        put.url = item_->url;
    } else {
        put.name = item_->name;
        put.mime = item_->mime;
        put.size = item_->size;
        put.sha256 = item_->sha256;
    }
    view_.put = PutProgress::sending;
    deadline_ = t + timing_.put_reply_s;
    deadline_code_ = "unreachable";
    deadline_why_ = "the screen did not answer the put";
    return {{std::move(put)}};
}

Step Pointer::received(double t, const p::Message& message) {
    const auto answers = [&](const std::optional<p::RequestId>& id) { return pending_ && id && *id == *pending_; };
    if (const auto* target = std::get_if<p::Target>(&message)) {
        see_target(*target);
    } else if (const auto* content = std::get_if<p::Content>(&message)) {
        if (view_.phase == Phase::grabbing && answers(content->id)) return on_content(*content);
    } else if (const auto* status = std::get_if<p::PutStatus>(&message)) {
        if (view_.phase == Phase::putting && answers(status->id)) return on_put_status(t, *status);
    } else if (const auto* error = std::get_if<p::Error>(&message)) {
        if ((view_.phase == Phase::grabbing || view_.phase == Phase::putting) && answers(error->id))
            return on_error(*error);
        if (error->code == p::ErrorCode::unauthorized) {
            finish({false, "unauthorized", "the provider revoked the pairing: " + error->message});
            view_.phase = Phase::failed;
            return {};
        }
        Step step;
        step.notice = *error;
        return step;
    }
    return {};
}

void Pointer::see_target(const p::Target& target) {
    if (view_.phase != Phase::locked || view_.mode != Mode::grab) return;
    view_.target_kind = target.kind;
    view_.target_title = target.title;
}

Step Pointer::on_content(const p::Content& content) {
    pending_.reset();
    deadline_.reset();
    const bool file = content.kind == p::ContentKind::file || content.kind == p::ContentKind::snapshot;
    if (file && (!content.download || !content.name || !content.size)) {
        finish({false, "protocol", "the provider's file has no download link, name or size", content});
    } else if (content.kind == p::ContentKind::url && !content.url) {
        finish({false, "protocol", "the provider's link has no url", content});
    } else if (file) {
        view_.phase = Phase::receiving;
        receiving_ = content;
        Step step;
        step.download = content;
        return step;
    } else {
        finish({true, {}, {}, content});
    }
    return {};
}

Step Pointer::downloaded(double, bool ok, const std::string& message) {
    if (view_.phase != Phase::receiving || !receiving_) return {};
    Outcome outcome{ok, ok ? std::string() : "download", message, std::move(receiving_)};
    receiving_.reset();
    finish(std::move(outcome));
    return {};
}

Step Pointer::on_put_status(double t, const p::PutStatus& status) {
    switch (status.status) {
        case p::PutState::asking:
            if (view_.put != PutProgress::asking) {
                view_.put = PutProgress::asking;
                view_.put_deadline = t + timing_.screen_answer_s;
                deadline_ = t + timing_.put_asking_s;
                deadline_why_ = "the screen did not answer within its " +
                                std::to_string(static_cast<int>(timing_.screen_answer_s)) + " s";
            }
            return {};
        case p::PutState::upload: {
            // The parser took only a path on the provider as the link (protocol/messages.hpp).
            if (item_->kind != p::ContentKind::file || view_.put == PutProgress::uploading) return {};
            view_.put = PutProgress::uploading;
            deadline_.reset();  // the upload reports how it went
            Step step;
            step.upload = status.upload;
            return step;
        }
        case p::PutState::done: finish({true, {}, {}, {}, status}); return {};
    }
    return {};
}

Step Pointer::uploaded(double t, int http_status, const std::optional<p::Message>& answer, const std::string& failure) {
    if (view_.phase != Phase::putting || view_.put != PutProgress::uploading) return {};
    if (answer) {
        if (const auto* status = std::get_if<p::PutStatus>(&*answer); status && status->status == p::PutState::done) {
            finish({true, {}, {}, {}, *status});
            return {};
        }
        if (const auto* error = std::get_if<p::Error>(&*answer)) {
            // A refused body is the upload broken off, whatever the HTTP layer called it.
            const auto code = error->code == p::ErrorCode::bad_request ? p::ErrorCode::interrupted : error->code;
            finish_failed(p::to_string(code), error->message);
            return {};
        }
    }
    view_.put = PutProgress::confirming;
    if (http_status == 200) {
        deadline_ = t + timing_.put_reply_s;
        deadline_code_ = "unreachable";
        deadline_why_ = "the screen did not confirm the upload";
    } else if (http_status == 0) {
        // The connection broke: the session usually says why first.
        deadline_ = t + timing_.broken_upload_grace_s;
        deadline_code_ = "interrupted";
        deadline_why_ = failure.empty() ? "the connection broke" : failure;
    } else {
        finish_failed("interrupted", "the upload was answered " + std::to_string(http_status));
    }
    return {};
}

Step Pointer::on_error(const p::Error& error) {
    finish_failed(p::to_string(error.code), error.message);
    return {};
}

Step Pointer::tick(double t) {
    if (!deadline_ || t < *deadline_) return {};
    if (view_.phase == Phase::grabbing || view_.phase == Phase::putting) finish_failed(deadline_code_, deadline_why_);
    deadline_.reset();
    return {};
}

Step Pointer::closed(double t, int code) {
    Step step;
    if (code == kScreenChangedCloseCode) {
        // The screen's layout changed: a new welcome brings the new field;
        // what was under way is abandoned, the put item kept.
        to_aiming(t);
        step.reconnect = true;
        return step;
    }
    finish({false, "unreachable", "connection closed, code " + std::to_string(code)});
    view_.phase = Phase::failed;
    return step;
}

void Pointer::choose_put(double t, PutItem item) {
    if (item.kind == p::ContentKind::url) {
        if (!http_url(item.url)) throw std::invalid_argument("a put's link must be an http or https URL");
        item.name.clear();
    } else if (item.kind == p::ContentKind::file) {
        if (item.name.empty() || item.size < 0) throw std::invalid_argument("a put's file needs a name and a size");
        // A name and type as the protocol takes them, whatever the phone's file system allowed.
        item.name = p::safe_file_name(item.name);
        if (!p::is_mime_type(item.mime)) item.mime = p::media_type_for(item.name);
    } else {
        throw std::invalid_argument("a put gives a link or a file");
    }
    item_ = std::move(item);
    view_.mode = Mode::put;
    to_aiming(t);
}

void Pointer::set_auto(bool on) { auto_act_ = on; }

void Pointer::leave_put(double t) {
    item_.reset();
    view_.mode = Mode::grab;
    to_aiming(t);
}

void Pointer::dismiss(double t) {
    if (view_.phase == Phase::result) to_aiming(t);
}

void Pointer::to_aiming(double t) {
    pending_.reset();
    deadline_.reset();
    receiving_.reset();
    view_.phase = Phase::searching;
    view_.put = PutProgress::none;
    view_.outcome.reset();
    view_.aim.reset();
    view_.target_kind.reset();
    view_.target_title.clear();
    view_.steady = view_.hint = false;
    steady_frames_ = 0;
    searching_since_ = t;
    started_ = true;
}

void Pointer::finish(Outcome outcome) {
    pending_.reset();
    deadline_.reset();
    view_.phase = Phase::result;
    view_.put = PutProgress::none;
    view_.steady = false;
    view_.aim.reset();
    view_.outcome = std::move(outcome);
}

void Pointer::finish_failed(const std::string& code, const std::string& message) {
    finish({false, code, message});
}

}  // namespace umf::requester_core
