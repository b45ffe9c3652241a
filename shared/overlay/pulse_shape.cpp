#include "shared/overlay/pulse_shape.hpp"

#include "shared/overlay/pulse.hpp"

namespace umf::overlay {

PulseShape announced_pulse_shape(Waveform waveform, double period_s, double opacity_min, double opacity_max) {
    Preset unit;  // the waveform over one period, 0 to 1
    unit.opacity_min = 0;
    unit.opacity_max = 1;
    unit.period_s = 1;
    unit.waveform = waveform;
    return PulseShape{[unit](double phase) { return opacity_at(unit, phase); }, period_s, opacity_min, opacity_max};
}

}  // namespace umf::overlay
