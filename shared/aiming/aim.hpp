// From one frame's detection to the aim message a requester sends
// (docs/PROTOCOL.md, "aim"). The native requester and the web client's
// WebAssembly module both build their aims here, so a phone and a webcam
// report the same point and confidence for the same frame.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "shared/detect/detector.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::aiming {

// A field point the protocol can carry: finite and within kMaxCoordinate.
bool usable_point(const Eigen::Vector2d& point);

// The detector's confidence as the protocol's 0..1 (NaN counts as 0).
double aim_confidence(const Detection& detection);

// The aim for `point` (the smoothed aim while tracking, or the detection's
// own); nullopt when the point is not usable.
std::optional<protocol::Aim> aim_message(const Eigen::Vector2d& point, const Detection& detection);

}  // namespace umf::aiming
