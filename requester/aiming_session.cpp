#include "requester/aiming_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include <opencv2/core.hpp>

#include "requester/grab_failure.hpp"
#include "requester/grey_frame.hpp"
#include "shared/aiming/aim.hpp"
#include "shared/detect/tracker.hpp"

namespace umf::requester {

namespace {

namespace p = protocol;
namespace core = requester_core;
using Clock = std::chrono::steady_clock;

// A recording without a frame rate: eight frames count as the steady half second.
constexpr double kFrameSecondsUnknownRate = 0.5 / 8;
constexpr double kDefaultCameraTimeoutS = 30.0;
// Unreadable frames in a row after which a camera counts as gone.
constexpr int kMaxBadFrames = 30;

using aiming::usable_point;

bool aiming(core::Phase phase) { return phase == core::Phase::searching || phase == core::Phase::locked; }

// A frame's result as the core takes it: the aim the protocol would carry.
core::Sighting sighting(bool locked, const Eigen::Vector2d& point, const Detection& d) {
    core::Sighting s;
    s.another_field = !locked && d.another_field;
    if (!locked || !usable_point(point)) return s;
    const std::optional<p::Aim> aim = aiming::aim_message(point, d);
    if (!aim) return s;
    s.locked = true;
    s.point = aim->point;
    s.confidence = aim->confidence;
    return s;
}

// What the preview says while the act goes on.
std::string progress_text(const core::View& v, double now) {
    switch (v.put) {
        case core::PutProgress::asking:
            return "waiting for the screen to accept (" +
                   std::to_string(static_cast<int>(std::max(0.0, std::ceil(v.put_deadline - now)))) + " s)";
        case core::PutProgress::confirming: return "waiting for the screen to confirm";
        case core::PutProgress::none: return v.phase == core::Phase::receiving ? "receiving" : "waiting for the screen";
        default: return "giving it to the screen";
    }
}

GrabFailure input_failure(const std::string& message) { return {"input", message, kInputError}; }

}  // namespace

void log(const std::string& line) { std::fprintf(stderr, "umf-requester: %s\n", line.c_str()); }

Json point_json(const p::FieldPoint& pt) {
    return Json::array({std::round(pt.u * 1000) / 1000, std::round(pt.v * 1000) / 1000});
}

Json failure_json(const std::string& code, const std::string& message) {
    Json j;
    j["ok"] = false;
    j["error"] = {{"code", code}, {"message", message}};
    return j;
}

int run_and_report(const std::function<Json()>& body, const std::optional<p::FieldPoint>& point, std::FILE* out) {
    try {
        write_line(out, body());
        return kOk;
    } catch (const GrabFailure& f) {
        log(f.what());
        Json j = failure_json(f.code, f.what());
        if (point) j["point"] = point_json(*point);
        write_line(out, j);
        return f.exit_code;
    } catch (const std::bad_alloc&) {
        log("out of memory");
        write_line(out, failure_json("internal", "out of memory"));
        return kInputError;
    } catch (const std::exception& e) {
        log(std::string("error: ") + e.what());
        write_line(out, failure_json("internal", e.what()));
        return kInputError;
    }
}

AimingSession::AimingSession(const PointingOptions& o, std::string client, std::optional<std::string> device)
    : o_(o),
      client_(std::move(client)),
      device_(std::move(device)),
      connection_(std::make_unique<ProviderConnection>(o.url)),
      paired_(o.paired) {}

AimingSession::~AimingSession() = default;

Json AimingSession::run(const std::function<void(const p::Welcome&)>& welcomed, const PointAction& action) {
    std::unique_ptr<FrameSource> source;
    Frame still;
    if (o_.input == FrameInput::image) {
        still = read_image_file(o_.path, 0);
        if (!still.error.empty()) throw input_failure(still.error);
    } else {
        try {
            source = o_.input == FrameInput::video ? video_file(o_.path) : camera(o_.camera_index);
        } catch (const InputError& e) {
            throw input_failure(e.what());
        }
    }

    p::Welcome welcome = connection_->open(client_, device_);
    log("connected to " + welcome.provider.name + " (" + welcome.provider.software + ") at " + o_.url.authority());
    welcomed_ = welcomed;
    if (welcomed_) welcomed_(welcome);
    take_welcome(std::move(welcome), action);
    tried_fingerprints_.push_back(o_.url.fingerprint);
    keep_as_used_last();

    Json result = o_.input == FrameInput::image ? act_on_still(still, action) : act_from(*source, action);
    connection_->close();
    return result;
}

void AimingSession::take_welcome(p::Welcome welcome, const PointAction& action) {
    std::unique_ptr<Detector> detector;
    try {
        detector = std::make_unique<Detector>(welcome.field.definition);
    } catch (const std::invalid_argument& e) {
        throw GrabFailure("protocol", std::string("the provider's field cannot be detected: ") + e.what(),
                          kConnection);
    }
    auto pointer = std::make_unique<core::Pointer>(welcome, core::Timing{}, o_.auto_act);
    if (action.put) {
        try {
            pointer->choose_put(0, *action.put);
        } catch (const std::invalid_argument& e) {
            throw input_failure(e.what());
        }
    }
    welcome_ = std::move(welcome);
    detector_ = std::move(detector);
    pointer_ = std::move(pointer);
    status_.provider = welcome_.provider.name;
    status_.another_screen = false;
}

bool AimingSession::switch_to_screen_in(const GreyView& view, const PointAction& action) {
    if (!o_.switch_screens) return false;
    const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
    for (const PairedScreen& screen : o_.paired) {
        if (std::find(tried_fingerprints_.begin(), tried_fingerprints_.end(), screen.url.fingerprint) !=
            tried_fingerprints_.end())
            continue;
        tried_fingerprints_.push_back(screen.url.fingerprint);
        try {
            auto connection = std::make_unique<ProviderConnection>(screen.url);
            p::Welcome welcome = connection->open(client_, device_);
            if (!Detector(welcome.field.definition).detect(view, centre).found) {
                connection->close();
                continue;
            }
            log("the screen " + where_frames() + " is " + welcome.provider.name +
                ", which this requester is paired with: switching to it");
            if (welcomed_) welcomed_(welcome);
            take_welcome(std::move(welcome), action);
            connection_->close();
            connection_ = std::move(connection);
            keep_as_used_last();
            return true;
        } catch (const GrabFailure& f) {
            log("not switching to the kept screen " + screen.name + " at " + screen.url.authority() + ": " + f.what());
        } catch (const std::invalid_argument& e) {
            log("the kept screen " + screen.name + " shows a field that cannot be detected: " + e.what());
        }
    }
    return false;
}

void AimingSession::keep_as_used_last() {
    const std::string& fingerprint = connection_->url().fingerprint;
    if (o_.paired_file.empty() || paired_.empty() || paired_.front().url.fingerprint == fingerprint) return;
    const auto it = std::find_if(paired_.begin(), paired_.end(),
                                 [&](const PairedScreen& s) { return s.url.fingerprint == fingerprint; });
    if (it == paired_.end()) return;  // only kept screens are kept
    try {
        paired_ = with_screen_first(paired_, *it);
        write_paired_screens(o_.paired_file, paired_);
    } catch (const InputError& e) {
        log(std::string("the screen used last cannot be noted: ") + e.what());
    }
}

void AimingSession::carry(const core::Step& step) {
    for (const auto& message : step.send) connection_->send(message);
    if (step.notice) {
        // Errors outside a request (a rate limit, a point off every screen): logged, once each.
        const std::string code = p::to_string(step.notice->code);
        if (code != last_logged_error_) log("the provider says " + code + ": " + step.notice->message);
        last_logged_error_ = code;
    }
}

void AimingSession::throw_if_failed() const {
    const core::View& v = pointer_->view();
    if (v.phase != core::Phase::failed || !v.outcome) return;
    throw GrabFailure(v.outcome->code == "unreachable" ? "connection" : v.outcome->code, v.outcome->message,
                      kConnection);
}

// What the provider said about aims: the title for the preview and the log.
void AimingSession::take_replies(double t) {
    for (auto& message : connection_->poll()) carry(pointer_->received(t, message));
    throw_if_failed();
}

void AimingSession::show_target() {
    const core::View& v = pointer_->view();
    status_.target_kind = v.target_kind ? p::to_string(*v.target_kind) : "";
    status_.target_title = v.target_title;
    if (v.target_kind && v.target_title != last_logged_title_) {
        log(std::string("aiming at ") + p::to_string(*v.target_kind) +
            (v.target_title.empty() ? "" : ": " + v.target_title));
        last_logged_title_ = v.target_title;
    }
}

Json AimingSession::act_on_still(const Frame& frame, const PointAction& action) {
    std::vector<std::uint8_t> luma;
    std::string why;
    const GreyView view = grey_view(frame.pixels, luma, why);
    if (!why.empty()) throw input_failure("cannot use " + frame.name + ": " + why);
    const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
    Detection d = detector_->detect(view, centre);
    // One photo: any other kept screen whose field it shows is worth asking.
    if (!d.found && switch_to_screen_in(view, action)) d = detector_->detect(view, centre);
    const core::Sighting seen = sighting(d.found, d.aim_field, d);
    if (seen.another_field) throw another_screen(frame.name);
    if (!seen.locked)
        throw GrabFailure("not_found_in_view",
                          "the field was not found in " + frame.name +
                              (d.failure.empty() ? std::string() : " (" + d.failure + ")") +
                              "; is the provider's field showing, and the whole screen sharp in the photo?",
                          kNothing);
    log("field point (" + std::to_string(d.aim_field.x()) + ", " + std::to_string(d.aim_field.y()) +
        ") under the image centre");
    const core::Step aimed = pointer_->frame(0, seen);
    carry(aimed);
    // The target says what is there; its absence or an error does not stop
    // the action, which has its own answer.
    for (const auto& message : aimed.send) {
        const auto* aim = std::get_if<p::Aim>(&message);
        if (!aim || !aim->id) continue;
        try {
            const p::Message reply = connection_->wait_reply(*aim->id, "aim");
            carry(pointer_->received(0, reply));
            show_target();
            if (const auto* e = std::get_if<p::Error>(&reply))
                log(std::string("the provider says ") + p::to_string(e->code) + ": " + e->message);
        } catch (const GrabFailure& f) {
            if (f.code != "timeout") throw;
            log(f.what());
        }
    }
    throw_if_failed();
    carry(pointer_->tap(0));
    return see_through(0, action);
}

Json AimingSession::act_from(FrameSource& source, const PointAction& action) {
    const bool live = source.live();
    const double fps = source.fps();
    const auto start = Clock::now();
    std::optional<double> timeout = o_.timeout_s;
    if (!timeout && live) timeout = kDefaultCameraTimeoutS;

    if (o_.window) preview_ = std::make_unique<Preview>("umf-requester " + action.verb);
    status_.provider = welcome_.provider.name;
    status_.auto_act = o_.auto_act;
    status_.verb = action.verb;

    auto tracker = std::make_unique<Tracker>(*detector_);
    std::vector<std::uint8_t> luma;
    bool ever_locked = false, ever_steady = false;
    int bad_frames = 0, frames = 0;

    while (true) {
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        if (timeout && elapsed > *timeout) end_without_act(action, ever_locked, ever_steady, true, *timeout);
        auto frame = source.next();
        if (!frame) {
            if (live) throw input_failure("the camera stopped giving frames");
            break;
        }
        std::string why = frame->error;
        GreyView view;
        if (why.empty()) view = grey_view(frame->pixels, luma, why);
        if (!why.empty()) {
            log(why);
            if (++bad_frames >= kMaxBadFrames) throw input_failure(why);
            continue;
        }
        bad_frames = 0;
        ++frames;
        // The frame's own time: a file is read faster than it was filmed.
        const double t = live ? elapsed : fps > 0 ? frame->index / fps : frames * kFrameSecondsUnknownRate;

        const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
        const TrackResult r = tracker->update(view, centre);
        take_replies(t);
        const bool locked = r.state == TrackState::locked;
        const core::Sighting seen = sighting(locked, r.aim_field, r.detection);
        carry(pointer_->frame(t, seen));
        show_target();
        if (seen.locked && !ever_locked) log("locked on the field");
        ever_locked = ever_locked || seen.locked;
        if (pointer_->view().another_screen && !status_.another_screen && switch_to_screen_in(view, action)) {
            tracker = std::make_unique<Tracker>(*detector_);
            continue;
        }
        if (pointer_->view().another_screen != status_.another_screen) {
            status_.another_screen = pointer_->view().another_screen;
            if (status_.another_screen) log(another_screen(where_frames()).what());
        }
        ever_steady = ever_steady || pointer_->view().steady;

        PreviewKey key = PreviewKey::none;
        status_.state = seen.locked ? PreviewState::locked : PreviewState::searching;
        if (preview_) {
            // A recording plays at its own pace for whoever watches it.
            const int wait_ms = !live && fps > 0 ? std::max(1, static_cast<int>(1000 / fps)) : 1;
            key = show(*preview_, frame->pixels, wait_ms);
        }
        if (key == PreviewKey::quit) throw GrabFailure("cancelled", "cancelled before a " + action.verb, kNothing);
        if (key == PreviewKey::act && !seen.locked) log("not locked on the field yet: point at the screen");
        if (key == PreviewKey::act && seen.locked) carry(pointer_->tap(t));
        if (!aiming(pointer_->view().phase)) {
            if (preview_) {
                last_frame_ = frame->pixels.clone();
                status_.state = PreviewState::acting;
                show(*preview_, last_frame_, 1);
            }
            return see_through(t, action);
        }
    }
    if (frames == 0) throw input_failure("the video " + o_.path + " has no frames OpenCV can read");
    end_without_act(action, ever_locked, ever_steady, false, 0);
}

Json AimingSession::see_through(double t0, const PointAction& action) {
    const auto start = Clock::now();
    const auto now = [&] { return t0 + std::chrono::duration<double>(Clock::now() - start).count(); };
    const p::FieldPoint at = pointer_->view().aim.value_or(p::FieldPoint{});
    acted_point_ = at;
    log(std::string(action.put ? "putting" : "grabbing") + " at (" + std::to_string(at.u) + ", " +
        std::to_string(at.v) + ")");
    core::Step step;
    core::PutProgress told = core::PutProgress::none;
    while (!pointer_->view().outcome) {
        if (step.download) {
            const p::Content content = *std::exchange(step.download, std::nullopt);
            action.download(content);
            step = pointer_->downloaded(now(), true);
        } else if (step.upload) {
            const std::string path = *std::exchange(step.upload, std::nullopt);
            step = pointer_->uploaded(now(), 200, p::Message{action.upload(path)});
        } else {
            const core::View& v = pointer_->view();
            if (v.put == core::PutProgress::asking && told != v.put)
                log("waiting for the person at the screen to accept it (up to 30 s)");
            told = v.put;
            show_progress(progress_text(v, now()));
            const auto arrived = connection_->wait_any(std::chrono::milliseconds(100));
            step = arrived.empty() ? pointer_->tick(now()) : core::Step{};
            for (const auto& message : arrived) {
                core::Step answer = pointer_->received(now(), message);
                carry(answer);
                if (answer.download) step.download = std::move(answer.download);
                if (answer.upload) step.upload = std::move(answer.upload);
            }
        }
        carry(step);
        step.send.clear();
    }
    throw_if_failed();
    return action.report(*pointer_->view().outcome, at);
}

void AimingSession::show_progress(const std::string& message) {
    if (!preview_ || last_frame_.empty()) return;
    status_.state = PreviewState::acting;
    status_.message = message;
    if (show(*preview_, last_frame_, 1) == PreviewKey::quit)
        throw GrabFailure("cancelled", "cancelled while " + message, kNothing);
}

PreviewKey AimingSession::show(Preview& preview, const cv::Mat& frame, int wait_ms) {
    try {
        return preview.show(frame, status_, wait_ms);
    } catch (const cv::Exception& e) {
        throw GrabFailure("input", "cannot show the preview window (" + e.err + "); use --no-window --auto",
                          kInputError);
    }
}

std::string AimingSession::where_frames() const {
    return o_.input == FrameInput::video ? "in " + o_.path : "in view";
}

GrabFailure AimingSession::another_screen(const std::string& where) const {
    return GrabFailure("another_screen",
                       "the screen " + where + " is another screen than " + welcome_.provider.name +
                           ": its field is not this screen's. Give --url that screen's pairing link, or keep it with "
                           "umf-requester pair URL and grab and put switch to it; or point at " +
                           welcome_.provider.name,
                       kNothing);
}

void AimingSession::end_without_act(const PointAction& action, bool ever_locked, bool ever_steady, bool timed_out,
                                    double timeout) const {
    const std::string where = where_frames();
    const std::string when = timed_out ? " within " + Json(timeout).dump() + " s" : "";
    if (!ever_locked && status_.another_screen) throw another_screen(where);
    if (!ever_locked)
        throw GrabFailure("not_found_in_view",
                          "the field was never found " + where + when +
                              "; is the provider's field showing, and the screen in view and in focus?",
                          kNothing);
    if (o_.auto_act && !ever_steady)
        throw GrabFailure("no_steady_lock",
                          "the field was found " + where + " but the aim never held steady for half a second" + when,
                          kNothing);
    throw GrabFailure("no_" + action.verb,
                      timed_out ? "no " + action.verb + when : "the video ended before a " + action.verb, kNothing);
}

}  // namespace umf::requester
