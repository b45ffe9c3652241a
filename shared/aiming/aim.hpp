// From one frame's detection to the aim message a requester sends
// (docs/PROTOCOL.md, "aim"). The native requester and the web client's
// WebAssembly module both build their aims here, so a phone and a webcam
// report the same point, view outline and confidence for the same frame.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

#include "detect/detector.hpp"
#include "protocol/messages.hpp"

namespace umf::aiming {

// A field point the protocol can carry: finite and within kMaxCoordinate.
bool usable_point(const Eigen::Vector2d& point);

// The detector's confidence as the protocol's 0..1 (NaN counts as 0).
double aim_confidence(const Detection& detection);

// The image's corners (top-left, top-right, bottom-right, bottom-left) in
// the field, for the provider's outline of the view; none when a corner lies
// beyond the horizon (on the other side of the homography's line at infinity
// than the image centre) or is not a usable point.
std::optional<std::array<protocol::FieldPoint, 4>> view_quad(const Eigen::Matrix3d& image_to_field, int width,
                                                             int height);

// The aim for `point` (the smoothed aim while tracking, or the detection's
// own) in an image of width x height; nullopt when the point is not usable.
std::optional<protocol::Aim> aim_message(const Eigen::Vector2d& point, const Detection& detection, int width,
                                         int height);

}  // namespace umf::aiming
