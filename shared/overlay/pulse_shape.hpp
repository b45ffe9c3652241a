// The pulse a provider announces (its welcome's waveform, period and opacities) as the
// pulse search fits it to a requester's frames (shared/detect/pulse_search.hpp).
#pragma once

#include "shared/detect/pulse_search.hpp"
#include "shared/overlay/preset.hpp"

namespace umf::overlay {

// `waveform` over `period_s` seconds, from 0 to 1 (opacity_at's shape),
// between the announced opacities (both 0: not announced).
PulseShape announced_pulse_shape(Waveform waveform, double period_s, double opacity_min = 0, double opacity_max = 0);

}  // namespace umf::overlay
