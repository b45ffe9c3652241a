#include "provider/desktop/wlroots/field_pixels.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace umf::provider {

namespace {

constexpr double kFocusSoftness = 0.15;  // as the X11 overlay's
// Distinct rows at this many opacity steps are kept; a pulse uses fewer.
constexpr std::size_t kCachedLevels = 64;

const std::uint32_t* layer_row(const QImage& layer, int y) {
    return reinterpret_cast<const std::uint32_t*>(layer.constScanLine(y));
}

}  // namespace

int opacity_level(double opacity) { return static_cast<int>(std::lround(std::clamp(opacity, 0.0, 1.0) * 255.0)); }

FocusMask focus_mask(QPointF centre, double radius, int width, int height) {
    FocusMask mask;
    if (radius <= 0) return mask;
    const int x0 = std::max(0, static_cast<int>(std::floor(centre.x() - radius)));
    const int y0 = std::max(0, static_cast<int>(std::floor(centre.y() - radius)));
    const int x1 = std::min(width, static_cast<int>(std::ceil(centre.x() + radius)) + 1);
    const int y1 = std::min(height, static_cast<int>(std::ceil(centre.y() + radius)) + 1);
    if (x1 <= x0 || y1 <= y0) return mask;
    mask.box = {x0, y0, x1 - x0, y1 - y0};
    mask.alpha.resize(static_cast<std::size_t>(mask.box.width) * mask.box.height);
    const double inner = radius * (1.0 - kFocusSoftness);
    for (int y = y0; y < y1; ++y) {
        const double dy = y + 0.5 - centre.y();
        std::uint8_t* out = &mask.alpha[static_cast<std::size_t>(y - y0) * mask.box.width];
        for (int x = x0; x < x1; ++x) {
            const double dx = x + 0.5 - centre.x();
            const double d = std::sqrt(dx * dx + dy * dy);
            const double m = d >= radius ? 0.0 : d <= inner ? 1.0 : (radius - d) / (radius - inner);
            out[x - x0] = static_cast<std::uint8_t>(std::lround(m * 255.0));
        }
    }
    return mask;
}

PulsedField::PulsedField(QImage layer) : layer_(layer.convertToFormat(QImage::Format_ARGB32_Premultiplied)) {
    int x0 = width(), y0 = height(), x1 = 0, y1 = 0;
    for (int y = 0; y < height(); ++y) {
        const std::uint32_t* row = layer_row(layer_, y);
        for (int x = 0; x < width(); ++x)
            if (row[x] != 0) {
                x0 = std::min(x0, x), x1 = std::max(x1, x + 1);
                y0 = std::min(y0, y), y1 = std::max(y1, y + 1);
            }
    }
    if (x1 <= x0) return;
    box_ = {x0, y0, x1 - x0, y1 - y0};
    const std::size_t bytes = static_cast<std::size_t>(box_.width) * 4;
    // Rows equal to the one above share it: a module row is one distinct row.
    for (int y = y0; y < y1; ++y) {
        const bool same = y > y0 && std::memcmp(layer_row(layer_, y) + x0, layer_row(layer_, y - 1) + x0, bytes) == 0;
        if (!same) group_first_row_.push_back(y);
        group_of_row_.push_back(static_cast<int>(group_first_row_.size()) - 1);
    }
}

const std::vector<std::uint32_t>& PulsedField::rows_at(int level) {
    if (const auto it = levels_.find(level); it != levels_.end()) return it->second;
    if (levels_.size() >= kCachedLevels) levels_.clear();
    std::vector<std::uint32_t> rows(group_first_row_.size() * static_cast<std::size_t>(box_.width));
    const auto factor = static_cast<std::uint32_t>(level) * 255u;
    for (std::size_t g = 0; g < group_first_row_.size(); ++g) {
        const std::uint32_t* in = layer_row(layer_, group_first_row_[g]) + box_.x;
        std::uint32_t* out = &rows[g * box_.width];
        for (int x = 0; x < box_.width; ++x) out[x] = in[x] == 0 ? 0 : scaled_pixel(in[x], factor);
    }
    return levels_.emplace(level, std::move(rows)).first->second;
}

void PulsedField::paint(std::uint8_t* pixels, int stride, int level) {
    if (box_.empty()) return;
    const auto& rows = rows_at(level);
    const std::size_t bytes = static_cast<std::size_t>(box_.width) * 4;
    for (int i = 0; i < box_.height; ++i) {
        auto* out = pixels + static_cast<std::size_t>(box_.y + i) * stride + static_cast<std::size_t>(box_.x) * 4;
        std::memcpy(out, &rows[static_cast<std::size_t>(group_of_row_[i]) * box_.width], bytes);
    }
}

void PulsedField::paint_focus(std::uint8_t* pixels, int stride, int level, const FocusMask& mask) const {
    const WindowRect& b = mask.box;
    for (int y = 0; y < b.height; ++y) {
        const std::uint32_t* in = layer_row(layer_, b.y + y) + b.x;
        const std::uint8_t* m = &mask.alpha[static_cast<std::size_t>(y) * b.width];
        auto* out = reinterpret_cast<std::uint32_t*>(pixels + static_cast<std::size_t>(b.y + y) * stride) + b.x;
        for (int x = 0; x < b.width; ++x)
            out[x] = m[x] == 0 || in[x] == 0 ? 0 : scaled_pixel(in[x], static_cast<std::uint32_t>(level) * m[x]);
    }
}

}  // namespace umf::provider
