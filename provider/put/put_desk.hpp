// The provider's side of puts (docs/PROTOCOL.md, "Put"), free of sockets: a
// put already validated, rate-limited and mapped to the screen is checked
// against the size limit and the folder's free space, then accepted at once
// for a trusted device (its files saved or opened as chosen with "always")
// or offered to the PutDecider; its answer (any
// thread, any time) becomes a message PUSHED to the requester's session
// through the outbox that session attached: an upload link, "done opened"
// or "refused". Offers not answered within answer_timeout are withdrawn and
// refused (a thread of its own watches the deadlines); a session that ends
// withdraws its offers. The upload itself (upload_route.hpp, PUT /up/...) reports
// back through upload_done and upload_failed. Each step (asked, accepted,
// refused, timed out, withdrawn, stored, opened, failed) goes to the
// activity listener (the console). What is opened is placed at the pointed
// place when the screen's rectangle is known (window_placement.hpp).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

#include "provider/common/activity.hpp"
#include "provider/content/resolver.hpp"
#include "provider/desktop/window_placement.hpp"
#include "provider/put/put_decision.hpp"
#include "provider/put/trusted_devices.hpp"
#include "provider/put/upload_table.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

// Who puts: the session and what its hello said.
struct PutRequester {
    std::uint64_t session = 0;  // SessionState::id
    std::string client;
    std::string device;  // empty: none given
};

class PutDesk : public std::enable_shared_from_this<PutDesk> {
public:
    // Takes an encoded message for the session; called on any thread, must
    // not block (a connection posts it to its strand).
    using Outbox = std::function<void(std::string encoded_message)>;

    // The rectangle of the welcome's screen `index` in X11 root-window
    // pixels; nullopt when unknown (nothing opened is moved then).
    using ScreenRects = std::function<std::optional<PlaceRect>(int index)>;

    // No decider: puts are refused (and the welcome names no "put" feature).
    // `activity` (may be null) hears each put's steps.
    static std::shared_ptr<PutDesk> create(std::shared_ptr<PutDecider> decider, PutSettings settings,
                                           std::shared_ptr<ActivityListener> activity = nullptr);
    ~PutDesk();
    PutDesk(const PutDesk&) = delete;
    PutDesk& operator=(const PutDesk&) = delete;

    bool enabled() const { return decider_ != nullptr; }
    const PutSettings& settings() const { return settings_; }

    // The immediate reply to a put: put_status asking (the answer is pushed
    // later), upload or done (a trusted device, or a decider that answered
    // within ask), or an error (refused, too_large, internal).
    protocol::Message offer(const PutRequester& who, const protocol::Put& put, std::optional<ScreenPoint> at);

    // Where a session's pushed messages go, from its welcome on.
    void attach(std::uint64_t session, Outbox outbox);
    // The session is gone: its outbox is dropped and its open offers withdrawn.
    void session_ended(std::uint64_t session);
    // Sends a message to a session's outbox; false when it has none.
    bool push(std::uint64_t session, const protocol::Message& message);

    // PUT /up/...: a request through an upload link begins (upload_table.hpp);
    // nullopt when the link is unknown, ended or expired.
    std::optional<UploadCheckout> begin_upload(std::string_view target);
    // The sink the link's first request made, or the one kept already.
    std::shared_ptr<UploadSink> keep_upload_sink(const UploadCheckout& checkout, std::shared_ptr<UploadSink> sink);
    // The request ended. A broken one leaves the link for the rest; if
    // nobody sends it within the link's lifetime, the session is told the
    // put failed (interrupted).
    void end_upload(const UploadCheckout& checkout, UploadEnd how);
    // The upload is stored as `stored_name`: put_status done (saved, or opened
    // after xdg-open for an `open` answer), pushed to the session and returned
    // for the HTTP answer.
    protocol::Message upload_done(const UploadEntry& entry, const std::string& stored_name);
    // The upload failed: the error, pushed to the session and returned.
    protocol::Error upload_failed(const UploadEntry& entry, protocol::ErrorCode code, const std::string& message);

    // Set before the server starts; not thread-safe against offers.
    void set_screen_rects(ScreenRects rects) { screen_rects_ = std::move(rects); }

    TrustedDevices& trusted() { return trusted_; }
    std::size_t offers_waiting() const;
    std::size_t uploads_waiting() const { return uploads_.size(); }
    // Withdraws every open offer and stops the deadline thread (the destructor does too).
    void stop();

private:
    struct Pending {
        PutOffer offer;
        std::uint64_t session = 0;
        protocol::RequestId id;
        std::string sha256;
        std::chrono::steady_clock::time_point deadline;
        bool in_ask = false;                // decider->ask has not returned yet
        std::optional<PutReply> early;      // answered within ask
    };

    PutDesk(std::shared_ptr<PutDecider> decider, PutSettings settings, std::shared_ptr<ActivityListener> activity);
    void answered(std::uint64_t offer, PutReply reply);
    // How the answer came: from the person asked, at once (a fixed policy),
    // or the device's standing choice.
    enum class Via { asked, at_once, trusted };
    protocol::Message act(const Pending& pending, const PutReply& reply, Via via);
    static PutActivity activity_of(const PutOffer& offer, std::uint64_t session, PutStage stage);
    void report(const PutOffer& offer, std::uint64_t session, PutStage stage, std::string detail = {},
                bool asked = true) const;
    void report(const UploadEntry& entry, PutStage stage, std::string path, std::string detail = {}) const;
    std::optional<WindowPlacement> placement(const std::optional<ScreenPoint>& at) const;
    std::unique_ptr<NewWindowWatch> window_watch(const std::optional<ScreenPoint>& at) const;
    void watch_deadlines();
    void start_watch_locked();

    std::shared_ptr<PutDecider> decider_;
    PutSettings settings_;
    TrustedDevices trusted_;
    UploadTable uploads_;
    std::shared_ptr<ActivityListener> activity_;
    ScreenRects screen_rects_;

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::map<std::uint64_t, Pending> pending_;
    std::uint64_t next_offer_ = 1;
    std::thread watcher_;
    bool stopping_ = false;

    mutable std::mutex outbox_mutex_;
    std::map<std::uint64_t, Outbox> outboxes_;
};

}  // namespace umf::provider
