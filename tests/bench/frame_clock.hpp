// "umf video" in real time (umf_benchmark --realtime): the camera films at
// its frame rate whatever the tracker does, and a device `slowdown` times
// slower than this machine takes that many times the measured time over
// each frame. A frame that arrives while the tracker is still busy with an
// earlier one is never looked at, as a page that always takes the newest
// camera frame skips it: it counts as not found ("dropped"). A search that
// stalls on a frame without the field thus costs the frames after it, where
// offline (slowdown 0) every frame is looked at however long it takes.
#pragma once

namespace umf::bench {

class FrameClock {
public:
    // slowdown 0: offline, every frame looked at.
    FrameClock(double slowdown, double fps) : slowdown_(slowdown), frame_ms_(1000.0 / fps) {}

    // This machine's time that is `share` of the time between two frames on
    // the device (0 offline).
    double machine_ms(double share) const { return slowdown_ > 0 ? share * frame_ms_ / slowdown_ : 0; }
    // Whether the tracker is free when frame `index` (counted from 0 at the
    // frame rate) arrives.
    bool free_for(int index) const { return !(slowdown_ > 0) || index * frame_ms_ >= busy_until_; }
    // The tracker took `ms` on this machine over frame `index`.
    void took(int index, double ms) {
        if (slowdown_ > 0) busy_until_ = index * frame_ms_ + ms * slowdown_;
    }

private:
    double slowdown_;
    double frame_ms_;
    double busy_until_ = 0;
};

inline constexpr char kDroppedFrame[] = "dropped: the tracker was still on an earlier frame";

}  // namespace umf::bench
