// What the requesters are doing, for the overlay and the console: who comes,
// who seeks, where each one aims and what it would take, what it takes, what
// it puts on the screen, when one leaves. The service calls these from
// the server's threads, concurrently; a listener hands them over to its own
// thread (the overlay's Qt thread) and must not block.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "provider/common/screen_point.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

struct AimActivity {
    std::uint64_t session = 0;  // stable for one welcomed session
    protocol::FieldPoint point;
    std::optional<ScreenPoint> screen;  // nullopt: the point lies on no screen
    double confidence = 0.0;
    protocol::ContentKind kind = protocol::ContentKind::none;
    std::string title;
};

struct WelcomeActivity {
    std::uint64_t session = 0;
    std::string client;  // as the hello said, for the person at the screen
    std::string peer;    // the remote address
};

// A hello turned away: a wrong pairing token, or an address that sent too
// many of them (then once, as the refusals begin).
struct RefusedActivity {
    std::string client;  // as the hello said
    std::string device;
    std::string peer;    // the remote address
    bool rate_limited = false;
};

struct GrabActivity {
    std::uint64_t session = 0;
    protocol::ContentKind kind = protocol::ContentKind::none;
    std::string title;
    std::string name;  // a file's or snapshot's
    std::int64_t size = 0;
};

// A put's steps (put/put_desk.hpp): offered and asked about, accepted or
// refused (by the person, by its deadline, by its requester leaving), then
// for a file stored or failed; a URL is opened as it is accepted.
enum class PutStage {
    asking,     // offered to the person at the screen
    accepted,   // answered save or open (or a trusted device's standing choice)
    refused,    // dismissed at the screen, or refused before asking (`detail` says why)
    timed_out,  // no answer in time
    withdrawn,  // the requester left before an answer
    stored,     // a file's bytes arrived and were saved (`path`)
    opened,     // a URL, or a saved file (`path`), handed to the desktop to open
    failed,     // accepted, but the upload or the opening went wrong (`detail`)
};

struct PutActivity {
    std::uint64_t session = 0;
    PutStage stage = PutStage::asking;
    protocol::ContentKind kind = protocol::ContentKind::file;
    std::string name;    // a file's safe name, or a URL's title (may be empty)
    std::string url;     // kind url
    std::int64_t size = 0;
    std::string client;  // the hello's `client`: what the phone calls itself ("Pixel 7 (umf web, Android)")
    std::string device;  // the hello's `device` (may be empty)
    std::string answer;  // accepted: "save" or "open"
    bool asked = false;    // accepted or refused: after an `asking` step (else by a trusted
                           // device's or a fixed policy's standing answer, or unfit to ask)
    bool trusted = false;  // accepted without asking: a device always accepted
    bool always = false;   // accepted with "always from this device"
    std::string path;    // stored and opened files: where the file is
    std::string detail;  // refused, timed_out, failed: why
};

class ActivityListener {
public:
    virtual ~ActivityListener() = default;
    virtual void welcomed(const WelcomeActivity&) {}
    virtual void refused(const RefusedActivity&) {}
    virtual void seeking(std::uint64_t session) = 0;
    virtual void aimed(const AimActivity& aim) = 0;
    // A grab answered with content (not with an error).
    virtual void grabbed(const GrabActivity&) {}
    // Each step of a put; called on any thread, possibly the Qt thread
    // itself (a prompt's answer).
    virtual void put(const PutActivity&) {}
    virtual void left(std::uint64_t session) = 0;
};

}  // namespace umf::provider
