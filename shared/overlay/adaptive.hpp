// The overlay following its requesters (thesis Ch. 10.2 and its future work):
// how strongly to mix the field, and where, from what requesters report.
// Pure and time-driven, so the provider's timer and the tests drive it alike.
//
// Requesters report through the protocol: `aim` (locked, with the detector's
// confidence) and `seeking` (camera on, no lock). The controller keeps the
// least visible field that still works: it lowers the opacity slowly while
// locks come easily and raises it fast when a requester struggles, always
// within the preset's range; the focus region grows the same way.
#pragma once

#include <optional>

#include "shared/overlay/preset.hpp"

namespace umf::overlay {

struct AdaptiveSettings {
    double easy_confidence = 0.9;  // aims at or above this count as easy
    double lower_per_s = 0.05;     // fraction of the preset's range given up per second of easy locks
    double raise_per_report = 0.25;  // fraction of the range added per struggling report
    double quiet_after_s = 3.0;    // with no report for this long, back to the full range (a new requester)
    double focus_grow = 1.5;       // factor on the focus radius per struggling report
    double focus_max_factor = 4.0; // the radius grows up to this many times the preset's
};

class AdaptiveOverlay {
public:
    AdaptiveOverlay(const Preset& preset, AdaptiveSettings settings = {});

    // A requester aimed with this confidence at t_s seconds.
    void aim(double t_s, double confidence);
    // A requester is seeking (no lock) at t_s.
    void seeking(double t_s);

    // 0..1: where in the preset's opacity range the pulse sits; 1 is the
    // preset as it is. Advances the slow lowering to t_s.
    double level(double t_s);
    // The pulse at t_s with its excursion above opacity_min scaled by the
    // level: never below opacity_min, the preset's floor.
    double opacity(double t_s);
    // The focus radius in modules: the preset's, grown while requesters struggle.
    double focus_radius_modules() const { return focus_radius_; }

private:
    void advance(double t_s);

    Preset preset_;
    AdaptiveSettings settings_;
    double level_ = 1.0;
    double focus_radius_;
    std::optional<double> last_t_;       // last time advanced to
    std::optional<double> last_report_;  // last aim or seeking
    bool easy_ = false;                  // the last report was an easy lock
};

}  // namespace umf::overlay
