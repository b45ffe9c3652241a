#include "provider/screen/desktop_layout.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>
#include <stdexcept>

namespace umf::provider {

namespace {

LaidOutScreen laid_out(const DesktopScreen& s, const ScreenField& whole, overlay::FieldPlacement placement) {
    LaidOutScreen laid;
    laid.screen = s;
    laid.field = whole;
    laid.field.screen_width = s.width;
    laid.field.screen_height = s.height;
    laid.field.placement = placement;
    const auto area = overlay::visible_area(placement, whole.field.width, whole.field.height, s.width, s.height);
    if (!area) throw std::invalid_argument("the field does not reach screen \"" + s.name + "\"");
    laid.region = *area;
    return laid;
}

// One field over the bounding box, as if it were one screen.
DesktopLayout shared_geometry(const std::vector<DesktopScreen>& screens, int left, int top, int right, int bottom,
                              const FieldSource& source) {
    const ScreenField whole = screen_field_for(right - left, bottom - top, screens[0].module_px, source);
    DesktopLayout layout{whole.field, whole.file, {}};
    for (const auto& s : screens) {
        // The same placement, seen from this screen's top-left corner.
        overlay::FieldPlacement p = whole.placement;
        p.origin_x += left - s.x;
        p.origin_y += top - s.y;
        layout.screens.push_back(laid_out(s, whole, p));
    }
    return layout;
}

DesktopLayout side_by_side(const std::vector<DesktopScreen>& screens, const FieldSource& source) {
    std::vector<std::size_t> order(screens.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::pair(screens[a].x, screens[a].y) < std::pair(screens[b].x, screens[b].y);
    });
    for (double factor = 1.0;; factor *= 1.1) {
        std::vector<int> module(screens.size()), columns(screens.size()), rows(screens.size());
        int total_columns = 0, most_rows = 0;
        for (std::size_t i = 0; i < screens.size(); ++i) {
            const auto& s = screens[i];
            const double wanted = s.module_px > 0 ? s.module_px : screen_field_for(s.width, s.height).placement.module_px;
            module[i] = std::max(1, static_cast<int>(std::lround(wanted * factor)));
            columns[i] = (s.width + module[i] - 1) / module[i];
            rows[i] = (s.height + module[i] - 1) / module[i];
            total_columns += columns[i];
            most_rows = std::max(most_rows, rows[i]);
        }
        // The screens' blocks of modules in a row, as one screen of one pixel
        // a module: it fits when that needs no larger module.
        const ScreenField whole = screen_field_for(total_columns, most_rows, 1.0, source);
        if (whole.placement.module_px != 1.0) continue;
        DesktopLayout layout{whole.field, whole.file, std::vector<LaidOutScreen>(screens.size())};
        double u = -whole.placement.origin_x;
        for (std::size_t i : order) {
            const double v = -whole.placement.origin_y + (most_rows - rows[i]) / 2;
            overlay::FieldPlacement p;
            p.module_px = module[i];
            p.origin_x = -u * module[i];
            p.origin_y = -v * module[i];
            layout.screens[i] = laid_out(screens[i], whole, p);
            u += columns[i];
        }
        return layout;
    }
}

}  // namespace

DesktopLayout lay_out_desktop(const std::vector<DesktopScreen>& screens, const FieldSource& source) {
    if (screens.empty()) throw std::invalid_argument("a desktop needs at least one screen");
    int left = INT_MAX, top = INT_MAX, right = INT_MIN, bottom = INT_MIN;
    for (std::size_t i = 0; i < screens.size(); ++i) {
        const auto& s = screens[i];
        if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384)
            throw std::invalid_argument("screen \"" + s.name + "\" has no usable size");
        for (std::size_t j = 0; j < i; ++j) {
            const auto& o = screens[j];
            if (s.x < o.x + o.width && o.x < s.x + s.width && s.y < o.y + o.height && o.y < s.y + s.height)
                throw std::invalid_argument("screens \"" + o.name + "\" and \"" + s.name +
                                            "\" overlap (mirrored screens show one field; turn mirroring off)");
        }
        left = std::min(left, s.x);
        top = std::min(top, s.y);
        right = std::max(right, s.x + s.width);
        bottom = std::max(bottom, s.y + s.height);
    }
    bool uniform = true;
    for (const auto& s : screens) uniform = uniform && std::lround(s.module_px) == std::lround(screens[0].module_px);
    return uniform ? shared_geometry(screens, left, top, right, bottom, source) : side_by_side(screens, source);
}

}  // namespace umf::provider
