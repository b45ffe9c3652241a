#include "shared/overlay/adaptive.hpp"

#include <algorithm>
#include <cmath>

#include "shared/overlay/pulse.hpp"

namespace umf::overlay {

AdaptiveOverlay::AdaptiveOverlay(const Preset& preset, AdaptiveSettings settings)
    : preset_(preset), settings_(settings), focus_radius_(preset.focus_radius_modules) {}

void AdaptiveOverlay::advance(double t_s) {
    if (last_t_ && t_s > *last_t_) {
        const double dt = t_s - *last_t_;
        if (last_report_ && t_s - *last_report_ > settings_.quiet_after_s) {
            // Nobody is looking: the next requester starts from the full preset.
            level_ = 1.0;
            easy_ = false;
            focus_radius_ = preset_.focus_radius_modules;
        } else if (easy_) {
            level_ = std::max(0.0, level_ - settings_.lower_per_s * dt);
        }
    }
    if (!last_t_ || t_s > *last_t_) last_t_ = t_s;
}

void AdaptiveOverlay::aim(double t_s, double confidence) {
    advance(t_s);
    last_report_ = t_s;
    easy_ = confidence >= settings_.easy_confidence;
    if (!easy_) {
        level_ = std::min(1.0, level_ + settings_.raise_per_report);
        focus_radius_ = std::min(focus_radius_ * settings_.focus_grow,
                                 preset_.focus_radius_modules * settings_.focus_max_factor);
    }
}

void AdaptiveOverlay::seeking(double t_s) {
    advance(t_s);
    last_report_ = t_s;
    easy_ = false;
    level_ = std::min(1.0, level_ + settings_.raise_per_report);
    focus_radius_ = std::min(focus_radius_ * settings_.focus_grow,
                             preset_.focus_radius_modules * settings_.focus_max_factor);
}

double AdaptiveOverlay::level(double t_s) {
    advance(t_s);
    return level_;
}

double AdaptiveOverlay::opacity(double t_s) {
    const double pulse = opacity_at(preset_, t_s);  // min..max
    const double min = preset_.opacity_min;
    // The pulse's excursion above the floor, scaled by the level.
    return min + (pulse - min) * level(t_s);
}

}  // namespace umf::overlay
