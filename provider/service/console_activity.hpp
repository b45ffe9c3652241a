// The person at the screen sees who connects, what they take and what they
// put: one line a welcome, a grab, each step of a put and a departure on the
// provider's console (aims and seeking are too many to print). Everything else goes on to the listener
// behind it (the overlay's, when there is one).
#pragma once

#include <memory>
#include <mutex>
#include <ostream>
#include <string>

#include "provider/common/activity.hpp"

namespace umf::provider {

class ConsoleActivity : public ActivityListener {
public:
    // `out` must outlive this; `next` may be null.
    ConsoleActivity(std::ostream& out, std::shared_ptr<ActivityListener> next);

    void welcomed(const WelcomeActivity& welcome) override;
    void refused(const RefusedActivity& refused) override;
    void seeking(std::uint64_t session) override;
    void aimed(const AimActivity& aim) override;
    void grabbed(const GrabActivity& grab) override;
    void put(const PutActivity& put) override;
    void left(std::uint64_t session) override;

private:
    void line(const std::string& text);

    std::ostream& out_;
    std::shared_ptr<ActivityListener> next_;
    std::mutex mutex_;
};

// Text from a requester or a window title made safe for a terminal: control
// characters (escape sequences among them) and Unicode bidirectional
// overrides shown as '?' (put/put_text.hpp, printable_text), at most
// max_bytes, never cut inside a UTF-8 character.
std::string printable(const std::string& text, std::size_t max_bytes = 128);

// The console's line for a put's step, without the newline.
std::string put_line(const PutActivity& put);

}  // namespace umf::provider
