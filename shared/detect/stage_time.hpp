// The detector's stage times: the milliseconds since a time stamp, which
// then moves on to now, so consecutive calls time consecutive stages.
#pragma once

#include <chrono>

namespace umf {

using StageClock = std::chrono::steady_clock;

inline double ms_since(StageClock::time_point& t) {
    const auto now = StageClock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - t).count();
    t = now;
    return ms;
}

}  // namespace umf
