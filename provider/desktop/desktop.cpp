#include "provider/desktop/desktop.hpp"

#include <algorithm>
#include <climits>

namespace umf::provider {

bool WindowRect::contains(double px, double py) const {
    return px >= x && py >= y && px < static_cast<double>(x) + width && py < static_cast<double>(y) + height;
}

bool WindowFilter::skips(const WindowInfo& window) const {
    return (window.pid > 0 && own_pids.count(window.pid)) ||
           (!window.instance.empty() && skip_classes.count(window.instance)) ||
           (!window.wm_class.empty() && skip_classes.count(window.wm_class));
}

WindowRect Desktop::screen() const {
    const auto all = outputs();
    if (all.empty()) return {};
    int left = INT_MAX, top = INT_MAX, right = INT_MIN, bottom = INT_MIN;
    for (const auto& output : all) {
        left = std::min(left, output.rect.x);
        top = std::min(top, output.rect.y);
        right = std::max(right, output.rect.x + output.rect.width);
        bottom = std::max(bottom, output.rect.y + output.rect.height);
    }
    return {left, top, right - left, bottom - top};
}

}  // namespace umf::provider
