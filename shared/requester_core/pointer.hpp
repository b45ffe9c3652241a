// The requester's rules, once for every requester (docs/ARCHITECTURE.md,
// "Requester core"): from the tracker's result for each frame, the user's
// taps, the provider's replies and the time, what to send (aims, seeking,
// grab, put), what to fetch or upload, and what the user sees. No I/O and no
// clock of its own: the caller says what happened and when, and carries out
// the Step it gets back. umf-requester drives it from its camera loop, the
// phone page through the WebAssembly module (pointer_json.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shared/protocol/messages.hpp"

namespace umf::requester_core {

// The rules' numbers. The defaults are the protocol's and the product's:
// a steady aim is held half a second within half a module, aims go at most
// 5 a second (fewer when the welcome's limit is lower), seeking once a second.
struct Timing {
    double steady_s = 0.5;
    double steady_modules = 0.5;
    int steady_min_frames = 3;  // a steady aim is seen in at least this many frames
    double max_aims_per_s = 5.0;
    double seeking_interval_s = 1.0;
    double hint_after_s = 6.0;     // searching this long: the user is told how to help
    // Another screen's field under the aim this long (frames without one
    // between them no more than another_gap_s apart): the user is pointing
    // at a screen this requester is not paired with.
    double another_screen_s = 1.0;
    double another_gap_s = 0.5;
    double grab_timeout_s = 20.0;  // a grab's answer
    double put_reply_s = 15.0;     // a put's first answer, and the screen's after the upload
    double screen_answer_s = 30.0;  // the screen's time to accept a put (its answer_timeout)
    double put_asking_s = 40.0;     // ... and some slack before the put counts as unanswered
    double broken_upload_grace_s = 2.0;  // an upload's connection broke: the session may still say why
};

// The close code of a session whose screen layout changed (docs/PROTOCOL.md):
// connect again for the new field.
inline constexpr int kScreenChangedCloseCode = 1012;

// What a frame showed: the tracker's aim while it is locked.
struct Sighting {
    bool locked = false;
    protocol::FieldPoint point;
    double confidence = 0.0;
    // Not locked because another screen's field is under the aim
    // (Detection::another_field).
    bool another_field = false;
};

// What Put mode gives the screen. A file needs name, mime and size; its
// sha256 may come later (hashed()), or after the bytes (hash_after: the
// put goes without it, and the upload names it).
struct PutItem {
    protocol::ContentKind kind = protocol::ContentKind::url;  // url or file
    std::string title;
    std::string url;
    std::string name;
    std::string mime;
    std::int64_t size = 0;
    std::optional<std::string> sha256;
    bool hash_after = false;
};

enum class Mode { grab, put };

enum class Phase {
    searching,  // no lock: the camera looks for the field
    locked,     // aiming: a tap grabs (puts)
    grabbing,   // a grab asked, its answer not here yet
    receiving,  // the grab's file is downloading
    putting,    // a put under way (PutProgress says where)
    result,     // a grab's or put's outcome is shown; dismiss() goes back to aiming
    failed,     // the session cannot go on (revoked pairing, connection lost)
};
const char* to_string(Phase phase);

enum class PutProgress { none, hashing, sending, asking, uploading, confirming };
const char* to_string(PutProgress progress);

// How a grab or put ended.
struct Outcome {
    bool ok = false;
    std::string code;     // when not ok: the provider's error code, or "unreachable", "interrupted", "download"
    std::string message;  // when not ok: why, for people
    std::optional<protocol::Content> content{};  // a grab's answer
    std::optional<protocol::PutStatus> put{};    // a put's final status
};

// What the user sees.
struct View {
    Mode mode = Mode::grab;
    Phase phase = Phase::searching;
    bool steady = false;   // the aim has held steady
    std::optional<protocol::FieldPoint> aim;
    // What the provider said lies at the aim; only while locked in grab mode
    // (in put mode what lies there is not where the put goes).
    std::optional<protocol::ContentKind> target_kind;
    std::string target_title;
    bool hint = false;  // searching for long: tell the user how to help the detector
    // Searching, and pointed at another screen than the paired one: "This is
    // another screen: scan its QR code".
    bool another_screen = false;
    PutProgress put = PutProgress::none;
    double put_deadline = 0;  // while asking: when the screen's time to answer runs out
    std::optional<Outcome> outcome;  // in result and failed

    // Grab (Put) is enabled: exactly while locked.
    bool can_act() const { return phase == Phase::locked; }
};

// What the caller does now, in this order: send the messages, then start the
// download or upload, then reconnect.
struct Step {
    std::vector<protocol::Message> send;
    std::optional<protocol::Content> download{};  // fetch this file, then call downloaded()
    std::optional<std::string> upload{};          // send the put's file to this path, then uploaded()
    bool reconnect = false;                       // the screen's layout changed: connect anew
    // An error the provider sent outside any request of ours (a rate limit,
    // a point off every screen): for a log line; nothing else changes.
    std::optional<protocol::Error> notice{};
};

class Pointer {
public:
    // `welcome`'s limits set the aim rate; `auto_act` grabs (puts) on a
    // steady aim without a tap.
    explicit Pointer(const protocol::Welcome& welcome, Timing timing = {}, bool auto_act = false);

    // One camera frame's result at time `t` (seconds, any origin, never going back).
    Step frame(double t, const Sighting& sighting);
    // The user taps Grab (Put) or the screen where the crosshair is.
    Step tap(double t);
    // A message from the provider.
    Step received(double t, const protocol::Message& message);
    // Time passes without a frame (timeouts).
    Step tick(double t);
    // The grab's download ended: `ok`, or failed with `message`.
    Step downloaded(double t, bool ok, const std::string& message = {});
    // The upload's HTTP answer: its status and the body it carried, when
    // the body was a message (a put_status, or the error envelope's error).
    Step uploaded(double t, int http_status, const std::optional<protocol::Message>& answer,
                  const std::string& failure = {});
    // A file item's SHA-256, when it was not known on choose_put.
    Step hashed(double t, const std::string& sha256);
    // The connection closed with this WebSocket close code (1006 when it broke).
    Step closed(double t, int code);

    // Put mode with `item` (a URL must be http(s); a file must have a name
    // and size; its name is made one the protocol takes, a type it does not
    // take is guessed from the name): aim as for a grab, then tap. Throws
    // std::invalid_argument.
    void choose_put(double t, PutItem item);
    // Acting by itself on a steady aim, from now on.
    void set_auto(bool on);
    // Back to grab mode; a put under way is abandoned.
    void leave_put(double t);
    // The user closes the result: aiming again.
    void dismiss(double t);

    const View& view() const { return view_; }
    const std::optional<PutItem>& put_item() const { return item_; }

private:
    protocol::RequestId next_id();
    void to_aiming(double t);
    void finish(Outcome outcome);
    // finish() with a failure: its code and why.
    void finish_failed(const std::string& code, const std::string& message);
    Step send_put(double t);
    Step on_content(const protocol::Content& content);
    Step on_put_status(double t, const protocol::PutStatus& status);
    Step on_error(const protocol::Error& error);
    void see_target(const protocol::Target& target);
    // Whether the user points at another screen, from this frame's sighting.
    void see_another_field(double t, const Sighting& sighting);

    Timing timing_;
    bool auto_act_ = false;
    double aim_interval_s_ = 0.2;
    View view_;
    std::optional<PutItem> item_;
    std::int64_t next_ = 2;  // 1 is the hello's
    // Aiming.
    std::optional<double> last_aim_, last_seeking_;
    double searching_since_ = 0;
    // Another screen's field: since when without a gap, and last seen.
    std::optional<double> another_since_, another_last_;
    bool started_ = false;
    protocol::FieldPoint anchor_;
    double steady_since_ = 0;
    int steady_frames_ = 0;
    // The request under way (a grab's or a put's id) and when it times out.
    std::optional<protocol::RequestId> pending_;
    protocol::FieldPoint pending_point_;
    std::optional<double> deadline_;
    std::string deadline_code_;
    std::string deadline_why_;
    std::optional<protocol::Content> receiving_;  // the grab's file while it downloads
};

}  // namespace umf::requester_core
