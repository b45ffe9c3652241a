#include "shared/detect/aim_check.hpp"

#include <cmath>

namespace umf {

bool aim_holds(const ModuleGrid& grid, int row0, int col0, const Eigen::Vector2d& aim_field, const WindowIndex& index,
               const VoteOptions& vote, const AimCheckOptions& o) {
    const Field& f = index.field();
    if (!aim_field.allFinite() || aim_field.x() < 0 || aim_field.y() < 0 || aim_field.x() >= f.width ||
        aim_field.y() >= f.height)
        return true;
    const int side = 2 * o.radius + 1;
    const int r = static_cast<int>(std::floor(aim_field.y())) - o.radius;
    const int c = static_cast<int>(std::floor(aim_field.x())) - o.radius;
    const ModuleGrid around = grid.crop(r - row0, c - col0, side, side);
    const GridPlacement here{0, r, c};
    const VoteResult local = vote_near(around, index, here, 1, vote);
    return local.placement.row_offset == r && local.placement.col_offset == c &&
           local.margin_bits >= o.min_margin_bits;
}

}  // namespace umf
