#include "shared/overlay/pulse.hpp"

#include <cmath>
#include <numbers>

namespace umf::overlay {

double opacity_at(const Preset& p, double t_s) {
    if (p.period_s <= 0.0 || !std::isfinite(t_s)) return p.opacity_max;
    // Phase in [0, 1) also for negative t, so the wave has no kink at 0.
    double phase = t_s / p.period_s;
    phase -= std::floor(phase);
    double rise;  // 0 at the minimum, 1 at the maximum
    if (p.waveform == Waveform::sine)
        rise = (1.0 - std::cos(2.0 * std::numbers::pi * phase)) / 2.0;
    else
        rise = phase < 0.5 ? 2.0 * phase : 2.0 - 2.0 * phase;
    return p.opacity_min + (p.opacity_max - p.opacity_min) * rise;
}

double presence(const Preset& p, std::optional<double> since_request_s) {
    if (p.activation == Activation::always) return 1.0;
    if (!since_request_s || std::isnan(*since_request_s)) return 0.0;
    double after_hold = *since_request_s - kOnDemandHoldS;
    if (after_hold <= 0.0) return 1.0;
    if (p.fade_s <= 0.0 || after_hold >= p.fade_s) return 0.0;
    return 1.0 - after_hold / p.fade_s;
}

double mixed_opacity(const Preset& p, double t_s, std::optional<double> since_request_s) {
    return opacity_at(p, t_s) * presence(p, since_request_s);
}

}  // namespace umf::overlay
