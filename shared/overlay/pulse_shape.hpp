// The pulse a provider announces (its welcome's waveform and period) as the
// pulse search fits it to a requester's frames (shared/detect/pulse_search.hpp).
#pragma once

#include "shared/detect/pulse_search.hpp"
#include "shared/overlay/preset.hpp"

namespace umf::overlay {

// `waveform` over `period_s` seconds, from 0 to 1 (opacity_at's shape).
PulseShape announced_pulse_shape(Waveform waveform, double period_s);

}  // namespace umf::overlay
