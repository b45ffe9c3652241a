// Motion blur along a curved path: a hand does not move the phone in straight
// lines during an exposure, it swings it in arcs, so each point of the screen
// smears along a curve (a straight smear is the special case of no turn).
#pragma once

#include <opencv2/core.hpp>

namespace umf::sim {

struct CurvedBlur {
    double length_px = 0;        // arc length of the smear in image pixels
    double start_angle_deg = 0;  // direction at the start, 0 = along +x, clockwise towards +y
    double turn_deg = 0;         // how far the direction turns along the smear (0 = straight)
};

// A normalised kernel: the arc splatted bilinearly in many points, centred on
// its centre of mass so the blurred picture does not shift.
cv::Mat curved_motion_kernel(const CurvedBlur& blur);

// Blurs linear light in place (nothing for length 0).
void apply_curved_motion(cv::Mat& linear, const CurvedBlur& blur);

}  // namespace umf::sim
