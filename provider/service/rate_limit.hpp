// A token bucket: `rate` events a second on average, bursts of up to
// `burst`. Used per session for aims and grabs (docs/PROTOCOL.md, "Limits")
// and per address for wrong pairing tokens.
#pragma once

#include <algorithm>
#include <chrono>

namespace umf::provider {

using SteadyTime = std::chrono::steady_clock::time_point;

class TokenBucket {
public:
    TokenBucket() = default;
    TokenBucket(double rate_per_s, double burst) : rate_(rate_per_s), burst_(burst), tokens_(burst) {}

    // True and one token taken when one is there.
    bool take(SteadyTime now) {
        refill(now);
        if (tokens_ < 1.0) return false;
        tokens_ -= 1.0;
        return true;
    }

private:
    void refill(SteadyTime now) {
        if (started_) {
            const double dt = std::chrono::duration<double>(now - last_).count();
            if (dt > 0) tokens_ = std::min(burst_, tokens_ + dt * rate_);
        }
        started_ = true;
        last_ = std::max(last_, now);
    }

    double rate_ = 1.0;
    double burst_ = 1.0;
    double tokens_ = 1.0;
    bool started_ = false;
    SteadyTime last_{};
};

}  // namespace umf::provider
