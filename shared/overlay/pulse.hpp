// The field's opacity over time: the pulse of a preset, and the on-demand
// presence that brings the field up while a requester looks for it.
#pragma once

#include <optional>

#include "shared/overlay/preset.hpp"

namespace umf::overlay {

// The pulse at t_s seconds from its start: opacity_min at t = 0, opacity_max
// half a period later, back to opacity_min after a period. Sine:
// min + (max - min)(1 - cos(2 pi t / T)) / 2; triangle: linear up, then down.
// A static preset (period 0) stays at opacity_max. Negative times continue
// the period backwards.
double opacity_at(const Preset& preset, double t_s);

// How long an on-demand field stays fully up after the last seeking or aim
// message: requesters repeat one at least every second (docs/PROTOCOL.md),
// so a gap shorter than this is not a requester gone.
inline constexpr double kOnDemandHoldS = 1.5;

// 0..1, the factor on the pulse: 1 for Activation::always; for on_demand 1
// within kOnDemandHoldS of the last request, then falling linearly to 0 over
// fade_s (at once when fade_s is 0), and 0 when no requester has asked
// (`since_request_s` empty).
double presence(const Preset& preset, std::optional<double> since_request_s);

// What the provider mixes at: opacity_at(t_s) * presence(since_request_s).
double mixed_opacity(const Preset& preset, double t_s, std::optional<double> since_request_s);

}  // namespace umf::overlay
