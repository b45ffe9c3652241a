#include "shared/aiming/aim.hpp"

#include <algorithm>
#include <cmath>

namespace umf::aiming {

namespace p = protocol;

bool usable_point(const Eigen::Vector2d& pt) {
    return std::isfinite(pt.x()) && std::isfinite(pt.y()) && std::abs(pt.x()) <= p::kMaxCoordinate &&
           std::abs(pt.y()) <= p::kMaxCoordinate;
}

double aim_confidence(const Detection& d) { return std::clamp(std::isfinite(d.confidence) ? d.confidence : 0.0, 0.0, 1.0); }

std::optional<p::Aim> aim_message(const Eigen::Vector2d& point, const Detection& d) {
    if (!usable_point(point)) return std::nullopt;
    p::Aim aim;
    aim.point = {point.x(), point.y()};
    aim.confidence = aim_confidence(d);
    return aim;
}

}  // namespace umf::aiming
