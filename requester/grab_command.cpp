#include "grab_command.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "cli.hpp"
#include "aiming/aim.hpp"
#include "detect/detector.hpp"
#include "detect/tracker.hpp"
#include "download.hpp"
#include "download_dir.hpp"
#include "field/field_io.hpp"
#include "frame_source.hpp"
#include "grab_failure.hpp"
#include "grey_frame.hpp"
#include "open_url.hpp"
#include "preview.hpp"
#include "protocol/messages.hpp"
#include "provider_connection.hpp"

namespace umf::requester {

const char* const kGrabUsage = R"(umf-requester grab: take what a provider's screen shows where the camera points

usage:
  umf-requester grab --url URL [--camera I | --video FILE | --image FILE]
                     [--out DIR] [--open] [--auto] [--no-window] [--timeout S]

Connects to the provider of the pairing URL (the certificate must have the URL's
fingerprint), finds the provider's marker field in the camera image and grabs
what is shown under the image centre: a link is printed, a file or a snapshot is
downloaded. A preview window shows the camera with a crosshair: a red banner
while the field is not found, a green ring and what a grab would take once it is;
space or Enter grabs, q or Esc quits.

options:
  --url URL       the pairing URL, https://HOST:PORT/#t=TOKEN&fp=FINGERPRINT
                  (umf-provider pair prints it)
  --camera I      camera number I (/dev/videoI); camera 0 when no input is given
  --video FILE    the frames of a video file instead of a camera
  --image FILE    one photo: detect once and grab at once (implies --auto)
  --out DIR       where downloads go (created if missing); default the desktop's
                  download directory (XDG_DOWNLOAD_DIR, else ~/Downloads). An
                  existing file is never replaced: "report (1).pdf" instead
  --open          open a grabbed link with xdg-open
  --auto          grab as soon as the aim holds steady (half a second within half
                  a module) instead of waiting for a key
  --no-window     no preview (also when there is no display); needs --auto
  --timeout S     give up after S seconds; camera default 30

Prints one JSON line at the end, progress goes to stderr:
  {"ok":true,"kind":"url","title":"...","point":[u,v],"url":"...","opened":false}
  {"ok":true,"kind":"file","title":"...","point":[u,v],"saved":"/abs/path",
   "name":"...","size":n,"sha256":"...","mime":"..."}          (also "snapshot")
  {"ok":false,"error":{"code":"...","message":"..."}}
error codes: usage, input, output, connection, certificate, unauthorized, timeout,
  protocol, not_found_in_view, no_steady_lock, no_grab, cancelled,
  nothing_to_take, download, and the provider's own (not_found, rate_limited,
  bad_request, too_large, internal, unsupported_version).

exit codes: 0 grabbed; 2 wrong usage; 3 the input could not be read or the file not
            written; 4 the provider could not be reached, its certificate did not
            match, it refused the token, or the exchange failed; 5 nothing was
            grabbed (no field in view, no steady aim, nothing at that point,
            the link expired, or cancelled).
)";

namespace {

namespace p = protocol;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr const char* kClient = "umf-requester/" UMF_VERSION;
// A steady aim: held this long and within this distance.
constexpr double kSteadySeconds = 0.5;
constexpr double kSteadyModules = 0.5;
// Without a frame rate, this many frames count as half a second.
constexpr int kSteadyFramesUnknownRate = 8;
// The protocol's aim rate: 2 to 5 a second while locked.
constexpr double kMaxAimsPerSecond = 5.0;
constexpr double kDefaultCameraTimeoutS = 30.0;
// Unreadable frames in a row after which a camera counts as gone.
constexpr int kMaxBadFrames = 30;

void log(const std::string& line) { std::fprintf(stderr, "umf-requester: %s\n", line.c_str()); }

bool has_display() {
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"})
        if (const char* v = std::getenv(name); v && *v) return true;
    return false;
}

double parse_seconds(const std::string& text) {
    char* end = nullptr;
    const double s = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(s) || s <= 0 || s > 86400)
        throw UsageError("--timeout must be a number of seconds within (0, 86400], not '" + text + "'");
    return s;
}

int parse_camera(const std::string& text) {
    if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string::npos)
        throw UsageError("--camera must be a camera number 0..999, not '" + text + "'");
    return std::stoi(text);
}

using aiming::usable_point;

Json point_json(const p::FieldPoint& pt) {
    // Thousandths of a module: the detector is not better than that.
    return Json::array({std::round(pt.u * 1000) / 1000, std::round(pt.v * 1000) / 1000});
}

GrabFailure input_failure(const std::string& message) { return {"input", message, kInputError}; }

// Everything one grab needs between its steps.
class GrabSession {
public:
    explicit GrabSession(const GrabOptions& o) : o_(o), connection_(o.url) {}

    Json run() {
        std::unique_ptr<FrameSource> source;
        Frame still;
        if (o_.input == GrabInput::image) {
            still = read_image_file(o_.path, 0);
            if (!still.error.empty()) throw input_failure(still.error);
        } else {
            try {
                source = o_.input == GrabInput::video ? video_file(o_.path) : camera(o_.camera_index);
            } catch (const InputError& e) {
                throw input_failure(e.what());
            }
        }

        welcome_ = connection_.open(kClient);
        log("connected to " + welcome_.provider.name + " (" + welcome_.provider.software + ") at " +
            o_.url.authority());
        try {
            detector_ = std::make_unique<Detector>(welcome_.field.definition);
        } catch (const std::invalid_argument& e) {
            throw GrabFailure("protocol", std::string("the provider's field cannot be detected: ") + e.what(),
                              kConnection);
        }

        Json result = o_.input == GrabInput::image ? grab_still(still) : grab_from(*source);
        connection_.close();
        return result;
    }

    std::optional<p::FieldPoint> grabbed_point() const { return grabbed_point_; }

private:
    p::RequestId next_id() { return p::RequestId{std::int64_t{id_++}}; }

    void send_aim(const Eigen::Vector2d& point, const Detection& d, int w, int h) {
        std::optional<p::Aim> aim = aiming::aim_message(point, d, w, h);
        if (!aim) return;
        aim->id = next_id();
        last_aim_id_ = aim->id;
        connection_.send(*aim);
    }

    // What the provider said about aims: the title for the preview; errors
    // (a rate limit, a point off every screen) only logged, once each.
    void take_replies() {
        for (auto& m : connection_.poll()) {
            if (const auto* t = std::get_if<p::Target>(&m)) {
                status_.target_kind = p::to_string(t->kind);
                status_.target_title = t->title;
                if (t->title != last_logged_title_) {
                    log(std::string("aiming at ") + p::to_string(t->kind) +
                        (t->title.empty() ? "" : ": " + t->title));
                    last_logged_title_ = t->title;
                }
            } else if (const auto* e = std::get_if<p::Error>(&m)) {
                if (e->code == p::ErrorCode::unauthorized)
                    throw GrabFailure("unauthorized", "the provider revoked the pairing: " + e->message, kConnection);
                const std::string code = p::to_string(e->code);
                if (code != last_logged_error_) log("the provider says " + code + ": " + e->message);
                last_logged_error_ = code;
            }
        }
    }

    Json grab_still(const Frame& frame) {
        std::vector<std::uint8_t> luma;
        std::string why;
        const GreyView view = grey_view(frame.pixels, luma, why);
        if (!why.empty()) throw input_failure("cannot use " + frame.name + ": " + why);
        const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
        const Detection d = detector_->detect(view, centre);
        if (!d.found || !usable_point(d.aim_field))
            throw GrabFailure("not_found_in_view",
                              "the field was not found in " + frame.name +
                                  (d.failure.empty() ? std::string() : " (" + d.failure + ")") +
                                  "; is the provider's field showing, and the whole screen sharp in the photo?",
                              kNothing);
        log("field point (" + std::to_string(d.aim_field.x()) + ", " + std::to_string(d.aim_field.y()) +
            ") under the image centre");
        send_aim(d.aim_field, d, view.width, view.height);
        // The target tells what the grab will take; its absence or an error
        // does not stop the grab, which has its own answer.
        try {
            const p::Message reply = connection_.wait_reply(*last_aim_id_, "aim");
            if (const auto* t = std::get_if<p::Target>(&reply))
                log(std::string("aiming at ") + p::to_string(t->kind) + (t->title.empty() ? "" : ": " + t->title));
            else if (const auto* e = std::get_if<p::Error>(&reply))
                log(std::string("the provider says ") + p::to_string(e->code) + ": " + e->message);
        } catch (const GrabFailure& f) {
            if (f.code != "timeout") throw;
            log(f.what());
        }
        return grab_at(d.aim_field);
    }

    Json grab_from(FrameSource& source) {
        const bool live = source.live();
        const double fps = source.fps();
        const double aims_per_s = std::min(welcome_.limits.aims_per_s, kMaxAimsPerSecond);
        const auto aim_interval = std::chrono::duration<double>(1.0 / aims_per_s);
        const auto seeking_interval = std::chrono::duration<double>(std::max(1.0, 1.0 / welcome_.limits.aims_per_s));
        const auto start = Clock::now();
        std::optional<double> timeout = o_.timeout_s;
        if (!timeout && live) timeout = kDefaultCameraTimeoutS;

        std::unique_ptr<Preview> preview;
        if (o_.window) preview = std::make_unique<Preview>("umf-requester grab - " + welcome_.provider.name);
        status_.provider = welcome_.provider.name;
        status_.auto_grab = o_.auto_grab;

        Tracker tracker(*detector_);
        std::vector<std::uint8_t> luma;
        // Never sent: due at once. (time_point::min() would overflow in now - min.)
        std::optional<Clock::time_point> last_aim, last_seeking;
        Eigen::Vector2d anchor(0, 0);
        int steady_frames = 0;
        double steady_since = 0;
        bool ever_locked = false, ever_steady = false;
        int bad_frames = 0, frames = 0;
        const int steady_frames_needed =
            fps > 0 ? std::max(2, static_cast<int>(std::ceil(kSteadySeconds * fps))) : kSteadyFramesUnknownRate;

        while (true) {
            const auto now = Clock::now();
            const double elapsed = std::chrono::duration<double>(now - start).count();
            if (timeout && elapsed > *timeout) end_without_grab(ever_locked, ever_steady, true, *timeout);
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
            const double t = live || fps <= 0 ? elapsed : frame->index / fps;

            const Eigen::Vector2d centre(view.width / 2.0, view.height / 2.0);
            const TrackResult r = tracker.update(view, centre);
            const bool locked = r.state == TrackState::locked && usable_point(r.aim_field);
            take_replies();
            if (locked) {
                if (!ever_locked) log("locked on the field");
                ever_locked = true;
                if (!last_aim || now - *last_aim >= aim_interval) {
                    send_aim(r.aim_field, r.detection, view.width, view.height);
                    last_aim = now;
                }
                if (steady_frames == 0 || (r.aim_field - anchor).norm() >= kSteadyModules) {
                    anchor = r.aim_field;
                    steady_frames = 1;
                    steady_since = t;
                } else {
                    ++steady_frames;
                }
            } else {
                if (steady_frames > 0) {
                    status_.target_kind.clear();
                    status_.target_title.clear();
                }
                steady_frames = 0;
                if (!last_seeking || now - *last_seeking >= seeking_interval) {
                    connection_.send(p::Seeking{});
                    last_seeking = now;
                }
            }
            const bool steady = steady_frames > 0 && (live ? t - steady_since >= kSteadySeconds && steady_frames >= 3
                                                           : steady_frames >= steady_frames_needed);
            ever_steady = ever_steady || steady;

            PreviewKey key = PreviewKey::none;
            status_.state = locked ? PreviewState::locked : PreviewState::searching;
            if (preview) {
                // A recording plays at its own pace for whoever watches it.
                const int wait_ms = !live && fps > 0 ? std::max(1, static_cast<int>(1000 / fps)) : 1;
                key = show(*preview, frame->pixels, wait_ms);
            }
            if (key == PreviewKey::quit) throw GrabFailure("cancelled", "cancelled before a grab", kNothing);
            if (key == PreviewKey::grab && !locked) log("not locked on the field yet: point at the screen");
            if (locked && ((o_.auto_grab && steady) || key == PreviewKey::grab)) {
                if (preview) {
                    status_.state = PreviewState::grabbing;
                    show(*preview, frame->pixels, 1);
                }
                return grab_at(r.aim_field);
            }
        }
        if (frames == 0) throw input_failure("the video " + o_.path + " has no frames OpenCV can read");
        end_without_grab(ever_locked, ever_steady, false, 0);
    }

    PreviewKey show(Preview& preview, const cv::Mat& frame, int wait_ms) {
        try {
            return preview.show(frame, status_, wait_ms);
        } catch (const cv::Exception& e) {
            throw GrabFailure("input", "cannot show the preview window (" + e.err + "); use --no-window --auto",
                              kInputError);
        }
    }

    [[noreturn]] void end_without_grab(bool ever_locked, bool ever_steady, bool timed_out, double timeout) const {
        const std::string where = o_.input == GrabInput::video ? "in " + o_.path : "in view";
        const std::string when = timed_out ? " within " + Json(timeout).dump() + " s" : "";
        if (!ever_locked)
            throw GrabFailure("not_found_in_view",
                              "the field was never found " + where + when +
                                  "; is the provider's field showing, and the screen in view and in focus?",
                              kNothing);
        if (o_.auto_grab && !ever_steady)
            throw GrabFailure("no_steady_lock",
                              "the field was found " + where + " but the aim never held steady for half a second" +
                                  when,
                              kNothing);
        throw GrabFailure("no_grab", timed_out ? "no grab" + when : "the video ended before a grab", kNothing);
    }

    Json grab_at(const Eigen::Vector2d& point) {
        const p::FieldPoint at{point.x(), point.y()};
        grabbed_point_ = at;
        const p::RequestId id{std::string("g1")};
        connection_.send(p::Grab{id, at});
        log("grabbing at (" + std::to_string(at.u) + ", " + std::to_string(at.v) + ")");
        const p::Message reply = connection_.wait_reply(id, "grab");
        if (const auto* e = std::get_if<p::Error>(&reply)) {
            const bool nothing = e->code == p::ErrorCode::not_found || e->code == p::ErrorCode::rate_limited;
            throw GrabFailure(p::to_string(e->code), "the provider refused the grab: " + e->message,
                              nothing ? kNothing : kConnection);
        }
        const auto* c = std::get_if<p::Content>(&reply);
        if (!c) throw GrabFailure("protocol", std::string("the provider answered the grab with a ") + p::type_name(reply),
                                  kConnection);

        Json j;
        j["ok"] = true;
        j["kind"] = p::to_string(c->kind);
        j["title"] = c->title;
        j["point"] = point_json(at);
        switch (c->kind) {
            case p::ContentKind::none:
                throw GrabFailure("nothing_to_take",
                                  "nothing to take at that point" +
                                      (c->title.empty() ? std::string() : " (" + c->title + ")"),
                                  kNothing);
            case p::ContentKind::url: {
                if (!c->url) throw GrabFailure("protocol", "the provider's link has no url", kConnection);
                j["url"] = *c->url;
                log("link: " + *c->url);
                j["opened"] = o_.open && open_url(*c->url);
                return j;
            }
            case p::ContentKind::file:
            case p::ContentKind::snapshot: {
                if (!c->download || !c->name || !c->size)
                    throw GrabFailure("protocol", "the provider's file has no download link, name or size",
                                      kConnection);
                const std::filesystem::path dir = o_.out ? std::filesystem::path(*o_.out) : default_download_dir();
                log("downloading " + *c->name + " (" + std::to_string(*c->size) + " bytes) to " + dir.string());
                const SavedFile saved = download_file(o_.url, {*c->download, *c->name, *c->size, c->sha256}, dir);
                log("saved " + saved.path.string());
                j["saved"] = saved.path.string();
                j["name"] = saved.name;
                j["size"] = saved.size;
                j["sha256"] = saved.sha256;
                if (c->mime) j["mime"] = *c->mime;
                return j;
            }
        }
        throw GrabFailure("protocol", "unknown content kind", kConnection);
    }

    const GrabOptions& o_;
    ProviderConnection connection_;
    p::Welcome welcome_;
    std::unique_ptr<Detector> detector_;
    std::int64_t id_ = 2;  // 1 is the hello's
    std::optional<p::RequestId> last_aim_id_;
    std::optional<p::FieldPoint> grabbed_point_;
    PreviewStatus status_;
    std::string last_logged_title_ = "\x01";
    std::string last_logged_error_;
};

void write_line(std::FILE* out, const Json& j) {
    const std::string line = j.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
    std::fwrite(line.data(), 1, line.size(), out);
    std::fflush(out);
}

Json failure_json(const std::string& code, const std::string& message) {
    Json j;
    j["ok"] = false;
    j["error"] = {{"code", code}, {"message", message}};
    return j;
}

}  // namespace

GrabOptions parse_grab_args(int argc, char** argv, int first) {
    const Args a = parse_args(argc, argv, first, {"url", "camera", "video", "image", "out", "timeout"},
                              {"open", "auto", "no-window"});
    if (!a.positional.empty()) throw UsageError("grab takes no file arguments; use --image FILE or --video FILE");
    GrabOptions o;
    const auto url = a.get("url");
    if (!url) throw UsageError("grab needs --url URL, the provider's pairing URL (umf-provider pair prints it)");
    try {
        o.url = parse_pairing_url(*url);
    } catch (const PairingUrlError& e) {
        throw UsageError(std::string("--url: ") + e.what());
    }
    const int inputs = (a.get("camera") ? 1 : 0) + (a.get("video") ? 1 : 0) + (a.get("image") ? 1 : 0);
    if (inputs > 1) throw UsageError("grab reads one of --camera, --video or --image");
    if (auto c = a.get("camera")) o.camera_index = parse_camera(*c);
    if (auto v = a.get("video")) {
        o.input = GrabInput::video;
        o.path = *v;
    }
    if (auto i = a.get("image")) {
        o.input = GrabInput::image;
        o.path = *i;
    }
    if ((o.input != GrabInput::camera) && o.path.empty()) throw UsageError("--video and --image need a file name");
    o.out = a.get("out");
    if (o.out && o.out->empty()) throw UsageError("--out needs a directory");
    o.open = a.has_flag("open");
    o.auto_grab = a.has_flag("auto") || o.input == GrabInput::image;
    if (auto t = a.get("timeout")) o.timeout_s = parse_seconds(*t);
    o.window = o.input != GrabInput::image && !a.has_flag("no-window") && has_display();
    if (o.input != GrabInput::image && !o.window && !o.auto_grab)
        throw UsageError(std::string(a.has_flag("no-window") ? "with --no-window" : "without a display ($DISPLAY is unset)") +
                         " no key can say when to grab: add --auto to grab on a steady aim");
    return o;
}

void write_usage_failure(std::FILE* out, const std::string& message) { write_line(out, failure_json("usage", message)); }

int run_grab(const GrabOptions& o, std::FILE* out) {
    std::optional<p::FieldPoint> point;
    try {
        GrabSession session(o);
        try {
            const Json result = session.run();
            write_line(out, result);
            return kOk;
        } catch (...) {
            point = session.grabbed_point();
            throw;
        }
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

}  // namespace umf::requester
