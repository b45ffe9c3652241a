// What the requesters are doing, for the overlay and the console: who comes,
// who seeks, where each one aims and what it would take, what it takes, when
// one leaves. The service calls these from
// the server's threads, concurrently; a listener hands them over to its own
// thread (the overlay's Qt thread) and must not block.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "content/resolver.hpp"

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

struct GrabActivity {
    std::uint64_t session = 0;
    protocol::ContentKind kind = protocol::ContentKind::none;
    std::string title;
    std::string name;  // a file's or snapshot's
    std::int64_t size = 0;
};

class ActivityListener {
public:
    virtual ~ActivityListener() = default;
    virtual void welcomed(const WelcomeActivity&) {}
    virtual void seeking(std::uint64_t session) = 0;
    virtual void aimed(const AimActivity& aim) = 0;
    // A grab answered with content (not with an error).
    virtual void grabbed(const GrabActivity&) {}
    virtual void left(std::uint64_t session) = 0;
};

}  // namespace umf::provider
