// Pointing at a provider's screen, what grab and put have in common:
// connect to the provider of the pairing URL, find its field in a camera, a
// video or one photo, aim (the provider shows the ring), wait for a steady
// aim or a key, and then act at the field point under the image centre. The
// act itself (take what is there, or give the screen something) is the
// caller's.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "requester/frame_source.hpp"
#include "requester/grab_failure.hpp"
#include "requester/json_lines.hpp"
#include "requester/pointing_options.hpp"
#include "requester/preview.hpp"
#include "requester/provider_connection.hpp"
#include "shared/detect/detector.hpp"
#include "shared/protocol/messages.hpp"
#include "shared/protocol/pairing_url.hpp"
#include "shared/requester_core/pointer.hpp"

namespace umf::requester {

// What to do once aimed. The requester core (requester_core/pointer.hpp)
// decides when and what to send; the command carries out what it asks for
// and turns its outcome into the JSON line.
struct PointAction {
    std::string verb;                            // "grab" or "put", for the preview and the log
    std::optional<requester_core::PutItem> put;  // Put mode's item; none: grab
    // The grab's file: fetch it, or throw GrabFailure.
    std::function<void(const protocol::Content&)> download;
    // The put's bytes to this upload path: the provider's final status, or throw GrabFailure.
    std::function<protocol::PutStatus(const std::string&)> upload;
    // The outcome at the point acted at: the JSON line's object, or throw GrabFailure.
    std::function<Json(const requester_core::Outcome&, const protocol::FieldPoint&)> report;
};

class AimingSession {
public:
    // `device`: the hello's device name, when the command has one.
    AimingSession(const PointingOptions& options, std::string client, std::optional<std::string> device = {});
    ~AimingSession();
    AimingSession(const AimingSession&) = delete;
    AimingSession& operator=(const AimingSession&) = delete;

    // Opens the input and the connection, calls `welcomed` with the welcome
    // (it may throw to stop before any aiming, e.g. when the provider lacks
    // a feature), aims until the core acts (a steady aim with --auto, or a
    // key), carries the grab or put through and returns action.report's
    // line. Throws GrabFailure for everything that ends it early.
    Json run(const std::function<void(const protocol::Welcome&)>& welcomed, const PointAction& action);

    // The session, for the action's own requests: the screen's it switched
    // to, if it did.
    ProviderConnection& connection() { return *connection_; }
    // The point the action ran at, once it has.
    std::optional<protocol::FieldPoint> acted_point() const { return acted_point_; }

    // While the action waits (for a person, an upload): the preview, if
    // any, shows the last frame with `message` and stays responsive. Throws
    // GrabFailure "cancelled" when the user quits meanwhile.
    void show_progress(const std::string& message);

private:
    // Sends what the core asks to; logs its notices.
    void carry(const requester_core::Step& step);
    // Gives the core what the provider said meanwhile.
    void take_replies(double t);
    // The target the core knows of, into the preview's status and the log.
    void show_target();
    // After the act: the core's requests, downloads and uploads until its outcome.
    Json see_through(double t, const PointAction& action);
    void throw_if_failed() const;
    Json act_on_still(const Frame& frame, const PointAction& action);
    Json act_from(FrameSource& source, const PointAction& action);
    PreviewKey show(Preview& preview, const cv::Mat& frame, int wait_ms);
    // "in view" or "in VIDEO": where the frames come from, for messages.
    std::string where_frames() const;
    // The failure of frames that show another screen's field (code another_screen).
    GrabFailure another_screen(const std::string& where) const;
    // The welcome's field into a detector and a core for the session.
    void take_welcome(protocol::Welcome welcome, const PointAction& action);
    // Pointed at another screen: the first of the kept screens not tried
    // yet whose field is in `view` becomes the session's screen. Returns
    // whether one did.
    bool switch_to_screen_in(const GreyView& view, const PointAction& action);
    // The screen kept with pair that this session uses goes first in the list.
    void keep_as_used_last();
    [[noreturn]] void end_without_act(const PointAction& action, bool ever_locked, bool ever_steady, bool timed_out,
                                      double timeout) const;

    const PointingOptions& o_;
    std::string client_;
    std::optional<std::string> device_;
    std::unique_ptr<ProviderConnection> connection_;
    protocol::Welcome welcome_;
    std::function<void(const protocol::Welcome&)> welcomed_;
    std::vector<std::string> tried_fingerprints_;  // the screens switch_to_screen_in tried
    std::vector<PairedScreen> paired_;             // the kept screens as this session last wrote them
    std::unique_ptr<Detector> detector_;
    std::unique_ptr<requester_core::Pointer> pointer_;
    std::optional<protocol::FieldPoint> acted_point_;
    PreviewStatus status_;
    std::unique_ptr<Preview> preview_;
    cv::Mat last_frame_;
    std::string last_logged_title_ = "\x01";
    std::string last_logged_error_;
};

// "[u, v]" rounded to thousandths of a module: the detector is not better.
Json point_json(const protocol::FieldPoint& point);

Json failure_json(const std::string& code, const std::string& message);

// Runs `body` and writes its JSON line, or the failure's line with the
// point acted at, when `point` holds one by then (the body sets it as the
// failure passes); returns the exit code.
int run_and_report(const std::function<Json()>& body, const std::optional<protocol::FieldPoint>& point,
                   std::FILE* out);

// Progress and failures on stderr: "umf-requester: ...".
void log(const std::string& line);

}  // namespace umf::requester
