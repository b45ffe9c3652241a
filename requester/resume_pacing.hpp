// When a transfer whose connection broke is tried again (docs/PROTOCOL.md,
// "Resuming a download", "Resuming an upload"): after 0.25 s, then 0.5, 1,
// 2 and 4 s, back to 0.25 s whenever the transfer got further than ever,
// and no more once nothing got further for the idle time. Downloads and
// uploads pace alike.
#pragma once

#include <chrono>
#include <cstdint>

namespace umf::requester {

class ResumePacing {
public:
    using Clock = std::chrono::steady_clock;

    explicit ResumePacing(std::chrono::milliseconds give_up_after) : give_up_after_(give_up_after) {}

    // The transfer stands at `bytes` (as the end that keeps them says).
    void reached(std::uint64_t bytes) {
        if (bytes <= furthest_) return;
        furthest_ = bytes;
        last_further_ = Clock::now();
        wait_ = kFirst;
    }
    std::uint64_t furthest() const { return furthest_; }
    // Nothing got further for the idle time, counting the next wait.
    bool given_up() const { return Clock::now() + wait_ - last_further_ > give_up_after_; }
    std::chrono::milliseconds next_wait() const { return wait_; }
    // Sleeps the next wait; the one after is twice as long, up to kLongest.
    void wait();

private:
    static constexpr std::chrono::milliseconds kFirst{250}, kLongest{4000};

    std::chrono::milliseconds give_up_after_;
    std::chrono::milliseconds wait_ = kFirst;
    std::uint64_t furthest_ = 0;
    Clock::time_point last_further_ = Clock::now();
};

}  // namespace umf::requester
