#include "aiming/aim.hpp"

#include <algorithm>
#include <cmath>

namespace umf::aiming {

namespace p = protocol;

bool usable_point(const Eigen::Vector2d& pt) {
    return std::isfinite(pt.x()) && std::isfinite(pt.y()) && std::abs(pt.x()) <= p::kMaxCoordinate &&
           std::abs(pt.y()) <= p::kMaxCoordinate;
}

double aim_confidence(const Detection& d) { return std::clamp(std::isfinite(d.confidence) ? d.confidence : 0.0, 0.0, 1.0); }

std::optional<std::array<p::FieldPoint, 4>> view_quad(const Eigen::Matrix3d& image_to_field, int w, int h) {
    const Eigen::Vector3d centre = image_to_field * Eigen::Vector3d(w / 2.0, h / 2.0, 1);
    const Eigen::Vector2d corners[4] = {{0, 0}, {double(w), 0}, {double(w), double(h)}, {0, double(h)}};
    std::array<p::FieldPoint, 4> quad;
    for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d q = image_to_field * Eigen::Vector3d(corners[i].x(), corners[i].y(), 1);
        if (!(q.z() * centre.z() > 0) || std::abs(q.z()) < 1e-12 * std::abs(centre.z())) return std::nullopt;
        const Eigen::Vector2d pt(q.x() / q.z(), q.y() / q.z());
        if (!usable_point(pt)) return std::nullopt;
        quad[i] = {pt.x(), pt.y()};
    }
    return quad;
}

std::optional<p::Aim> aim_message(const Eigen::Vector2d& point, const Detection& d, int w, int h) {
    if (!usable_point(point)) return std::nullopt;
    p::Aim aim;
    aim.point = {point.x(), point.y()};
    aim.quad = view_quad(d.image_to_field, w, h);
    aim.confidence = aim_confidence(d);
    return aim;
}

}  // namespace umf::aiming
